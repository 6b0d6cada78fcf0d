// SPDX-License-Identifier: LGPL-2.1-or-later
// Copyright (C) 2026 by the grainmpm authors

#include <grainmpm/base/input_error.h>
#include <grainmpm/base/parameter_file.h>
#include <grainmpm/base/parameter_parsing.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace grainmpm
{
  using namespace dealii;

  namespace
  {
    /**
     * The base name of @p path, quoted: messages that do not depend on
     * where the files are.
     */
    std::string
    quoted_file_name(const std::string &path)
    {
      return "'" + std::filesystem::path(path).filename().string() + "'";
    }



    /**
     * Throw an InputError unless @p filename is a regular file that can be
     * read; @p chain names the files that include it.
     */
    void
    check_readable(const std::string              &filename,
                   const std::vector<std::string> &chain)
    {
      const std::string from =
        chain.empty() ?
          "" :
          " (included from " + quoted_file_name(chain.back()) + ")";
      std::error_code code;
      if (!std::filesystem::exists(filename, code))
        throw InputError("",
                         "the parameter file '" + filename +
                           "' does not exist" + from + ".");
      if (!std::filesystem::is_regular_file(filename, code))
        throw InputError("",
                         "'" + filename +
                           "' is not a parameter file but a directory or "
                           "a device" +
                           from + ".");
      if (!std::ifstream(filename))
        throw InputError("",
                         "the parameter file '" + filename +
                           "' cannot be read" + from + ".");
    }



    /**
     * Follow the include lines of the `.prm` file @p filename (the files
     * @p chain includes it through) and throw an InputError if a file
     * includes itself or cannot be read.
     */
    void
    check_includes(const std::string       &filename,
                   std::vector<std::string> chain = {})
    {
      const std::string name =
        std::filesystem::weakly_canonical(filename).string();
      if (std::find(chain.begin(), chain.end(), name) != chain.end())
        {
          std::string through;
          for (const auto &file : chain)
            through += quoted_file_name(file) + " -> ";
          throw InputError("",
                           "the parameter file " + quoted_file_name(name) +
                             " includes itself: " + through +
                             quoted_file_name(name) +
                             ". Remove the include line.");
        }
      check_readable(filename, chain);
      chain.push_back(name);
      std::ifstream in(filename);
      std::string   line;
      while (std::getline(in, line))
        {
          line = Utilities::trim(strip_comment(line));
          if (line.rfind("include ", 0) == 0 || line.rfind("INCLUDE ", 0) == 0)
            check_includes(Utilities::trim(line.substr(8)), chain);
        }
    }



    /** The format told by the extension of @p filename, unchecked. */
    ParameterFileFormat
    format_of(const std::string &filename)
    {
      const std::string extension =
        std::filesystem::path(filename).extension().string();
      if (extension == ".json")
        return ParameterFileFormat::json;
      if (extension == ".xml")
        return ParameterFileFormat::xml;
      return ParameterFileFormat::prm;
    }



    /**
     * The name @p name as deal.II writes it in XML, where every character
     * other than a letter or a digit is '_' and two hexadecimal digits,
     * turned back into the name.
     */
    std::string
    demangle(const std::string &name)
    {
      std::string plain;
      for (std::size_t i = 0; i < name.size(); ++i)
        if (name[i] == '_' && i + 2 < name.size() &&
            std::isxdigit(static_cast<unsigned char>(name[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(name[i + 2])))
          {
            plain += static_cast<char>(std::stoi(name.substr(i + 1, 2), 0, 16));
            i += 2;
          }
        else
          plain += name[i];
      return plain;
    }



    /**
     * The tree of the `.json` or `.xml` file @p filename, from the node
     * that holds the top-level entries. Throws an InputError naming the
     * file and the line if it is not valid.
     */
    boost::property_tree::ptree
    read_tree(const std::string &filename, const ParameterFileFormat format)
    {
      boost::property_tree::ptree tree;
      try
        {
          if (format == ParameterFileFormat::json)
            boost::property_tree::read_json(filename, tree);
          else
            boost::property_tree::read_xml(filename, tree);
        }
      catch (const boost::property_tree::file_parser_error &error)
        {
          throw InputError("",
                           "the parameter file " + quoted_file_name(filename) +
                             " is not valid " +
                             (format == ParameterFileFormat::json ? "JSON" :
                                                                    "XML") +
                             ": " + error.message() + " at line " +
                             std::to_string(error.line()) + ".");
        }
      if (format == ParameterFileFormat::xml)
        {
          const auto root = tree.get_child_optional("ParameterHandler");
          if (!root)
            throw InputError("",
                             "the XML parameter file " +
                               quoted_file_name(filename) +
                               " has no root element <ParameterHandler> (as "
                               "`grainmpm --print-parameters 2 xml` writes "
                               "it).");
          return *root;
        }
      return tree;
    }
  } // namespace



  ParameterFileFormat
  check_parameter_file(const std::string &filename)
  {
    const std::string extension =
      std::filesystem::path(filename).extension().string();
    if (extension != ".prm" && extension != ".json" && extension != ".xml")
      {
        check_readable(filename, {});
        throw InputError("",
                         "the parameter file " + quoted_file_name(filename) +
                           " has " +
                           (extension.empty() ?
                              std::string("no extension") :
                              "the extension '" + extension + "'") +
                           ": grainmpm reads .prm, .json and .xml parameter "
                           "files and tells their format by the extension. "
                           "Rename the file.");
      }
    const ParameterFileFormat format = format_of(filename);
    if (format == ParameterFileFormat::prm)
      check_includes(filename);
    else
      {
        check_readable(filename, {});
        read_tree(filename, format);
      }
    return format;
  }



  std::vector<std::string>
  find_subsections(const std::string &filename, const std::string &parent)
  {
    std::vector<std::string> names;
    const auto               add = [&names](const std::string &name) {
      if (std::find(names.begin(), names.end(), name) == names.end())
        names.push_back(name);
    };

    const ParameterFileFormat format = format_of(filename);
    if (format != ParameterFileFormat::prm)
      {
        // A subsection is a node with children of its own that is not an
        // entry written with its value, default and documentation.
        const boost::property_tree::ptree tree = read_tree(filename, format);
        for (const auto &[key, node] : tree)
          {
            const std::string name =
              format == ParameterFileFormat::xml ? demangle(key) : key;
            if (name != parent)
              continue;
            for (const auto &[child_key, child] : node)
              if (!child.empty() && child.count("value") == 0)
                add(format == ParameterFileFormat::xml ? demangle(child_key) :
                                                         child_key);
          }
        return names;
      }

    std::ifstream in(filename);
    if (!in)
      throw InputError("",
                       "cannot open the parameter file '" + filename + "'.");
    std::vector<std::string> stack;
    std::string              line;
    while (std::getline(in, line))
      {
        line = strip_comment(line);
        if (line.rfind("subsection ", 0) == 0)
          {
            const std::string name = Utilities::trim(line.substr(11));
            if (stack.size() == 1 && stack[0] == parent)
              add(name);
            stack.push_back(name);
          }
        else if (line == "end" && !stack.empty())
          stack.pop_back();
        else if (line.rfind("include ", 0) == 0 && stack.empty())
          for (const auto &name :
               find_subsections(Utilities::trim(line.substr(8)), parent))
            add(name);
      }
    return names;
  }



  std::string
  subsection_path_at_line(const std::string &filename, const unsigned int line)
  {
    std::ifstream            in(filename);
    std::vector<std::string> stack;
    std::string              text;
    for (unsigned int number = 1; number < line && std::getline(in, text);
         ++number)
      {
        text = strip_comment(text);
        if (text.rfind("subsection ", 0) == 0)
          stack.push_back(Utilities::trim(text.substr(11)));
        else if (text == "end" && !stack.empty())
          stack.pop_back();
      }
    std::string path;
    for (const auto &name : stack)
      path += (path.empty() ? "" : "/") + name;
    return path;
  }



  unsigned int
  read_dimension(const std::string &filename)
  {
    check_parameter_file(filename);
    ParameterHandler prm;
    prm.declare_entry("Dimension",
                      "2",
                      Patterns::Integer(2, 3),
                      "The space dimension of the run, 2 or 3.");
    prm.parse_input(filename, "", true, false);
    return prm.get_integer("Dimension");
  }



  std::string
  expand_includes(const std::string &filename)
  {
    std::ifstream in(filename);
    if (format_of(filename) != ParameterFileFormat::prm)
      {
        std::ostringstream text;
        text << in.rdbuf();
        return text.str();
      }
    std::string text, line;
    while (std::getline(in, line))
      {
        const std::string command = Utilities::trim(strip_comment(line));
        if (command.rfind("include ", 0) == 0 ||
            command.rfind("INCLUDE ", 0) == 0)
          {
            const std::string included = Utilities::trim(command.substr(8));
            text += "# " + line + " (expanded below)\n" +
                    expand_includes(included) + "# end of " + included + "\n";
          }
        else
          text += line + '\n';
      }
    return text;
  }



  std::string
  original_file_name(const std::string &filename)
  {
    switch (format_of(filename))
      {
        case ParameterFileFormat::json:
          return "original.json";
        case ParameterFileFormat::xml:
          return "original.xml";
        case ParameterFileFormat::prm:
          break;
      }
    return "original.prm";
  }
} // namespace grainmpm
