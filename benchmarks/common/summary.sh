# SPDX-License-Identifier: LGPL-2.1-or-later
# Copyright (C) 2026 by the grainmpm authors
#
# Reading summary.csv, the machine-readable summary that every run writes
# into its output directory (doc/output.md lists its quantities). Source it.

# summary_value FILE QUANTITY [FORMAT]: the value of QUANTITY in the
# summary.csv FILE, as written (17 digits), or printed with the printf
# FORMAT (e.g. "%.6g": six significant digits, as the screen summary
# prints it). A missing quantity is an error.
summary_value() {
  awk -F, -v quantity="$2" -v format="${3:-%s}" '
    $1 == quantity { printf format, $2; found = 1 }
    END { if (!found) { printf "no %s in %s\n", quantity, FILENAME > "/dev/stderr"; exit 1 } }' "$1"
}
