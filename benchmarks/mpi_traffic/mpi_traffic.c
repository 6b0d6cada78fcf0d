/* SPDX-License-Identifier: LGPL-2.1-or-later
 * Copyright (C) 2026 by the grainmpm authors
 *
 * A PMPI interposer that counts what a process sends: loaded with
 * LD_PRELOAD into every rank of an MPI run, it counts the point-to-point
 * messages and their bytes, and the collective calls and the bytes each
 * rank contributes to them, and writes one line per rank at MPI_Finalize to
 * the file $MPI_TRAFFIC_OUTPUT.<rank> (default mpi_traffic.<rank>):
 *
 *   rank R p2p_messages M p2p_bytes B collectives C collective_bytes D
 *   mpi_seconds S
 *   calls NAME COUNT NAME COUNT ...
 *
 * Only the sending side of point-to-point calls is counted (each message
 * once), blocking and non-blocking, synchronous and buffered. The
 * collectives are counted per call, with the bytes of the calling rank's
 * send buffer (count x type size; for the v-variants the sum of its send
 * counts). S is the wall time spent inside the MPI calls, the waits,
 * receives, probes and tests included: time moving data or waiting for
 * another rank. The second line counts the calls of every wrapped
 * function that was called. Used by benchmarks/communication_volume.sh; a run
 * of 1 and a run of N steps give the traffic of N - 1 steps by difference.
 */

#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

static long long p2p_messages     = 0;
static long long p2p_bytes        = 0;
static long long collectives      = 0;
static long long collective_bytes = 0;
static double    mpi_seconds      = 0.;

/* Calls per function. */
enum Function
{
  f_Send,
  f_Ssend,
  f_Bsend,
  f_Isend,
  f_Issend,
  f_Sendrecv,
  f_Barrier,
  f_Ibarrier,
  f_Bcast,
  f_Allreduce,
  f_Iallreduce,
  f_Reduce,
  f_Scan,
  f_Exscan,
  f_Allgather,
  f_Allgatherv,
  f_Gather,
  f_Gatherv,
  f_Alltoall,
  f_Alltoallv,
  f_Reduce_scatter_block,
  f_Scatter,
  f_Recv,
  f_Probe,
  f_Iprobe,
  f_Wait,
  f_Waitall,
  f_Waitany,
  f_Waitsome,
  f_Test,
  f_Testall,
  n_functions
};

static const char *function_names[n_functions] = {
  "Send",       "Ssend",      "Bsend",
  "Isend",      "Issend",     "Sendrecv",
  "Barrier",    "Ibarrier",   "Bcast",
  "Allreduce",  "Iallreduce", "Reduce",
  "Scan",       "Exscan",     "Allgather",
  "Allgatherv", "Gather",     "Gatherv",
  "Alltoall",   "Alltoallv",  "Reduce_scatter_block",
  "Scatter",    "Recv",       "Probe",
  "Iprobe",     "Wait",       "Waitall",
  "Waitany",    "Waitsome",   "Test",
  "Testall"};
static long long calls[n_functions] = {0};

/* Call and return @p call, adding its wall time to mpi_seconds. */
#define TIMED(call)                         \
  do                                        \
    {                                       \
      const double start_  = PMPI_Wtime();  \
      const int    result_ = call;          \
      mpi_seconds += PMPI_Wtime() - start_; \
      return result_;                       \
    }                                       \
  while (0)

static long long
bytes_of(const int count, MPI_Datatype type)
{
  int size = 0;
  if (type == MPI_DATATYPE_NULL)
    return 0;
  PMPI_Type_size(type, &size);
  return (long long)count * size;
}

static void
count_send(const int count, MPI_Datatype type, const int destination)
{
  if (destination == MPI_PROC_NULL)
    return;
  ++p2p_messages;
  p2p_bytes += bytes_of(count, type);
}

static void
count_collective(const long long bytes)
{
  ++collectives;
  collective_bytes += bytes;
}

static long long
sum_of_counts(const int *counts, MPI_Datatype type, MPI_Comm comm)
{
  int size = 0, rank = 0;
  PMPI_Comm_size(comm, &size);
  PMPI_Comm_rank(comm, &rank);
  long long sum = 0;
  for (int r = 0; r < size; ++r)
    if (r != rank)
      sum += bytes_of(counts[r], type);
  return sum;
}

/* Point to point. */
int
MPI_Send(const void  *buf,
         int          count,
         MPI_Datatype type,
         int          dest,
         int          tag,
         MPI_Comm     comm)
{
  ++calls[f_Send];
  count_send(count, type, dest);
  TIMED(PMPI_Send(buf, count, type, dest, tag, comm));
}

int
MPI_Ssend(const void  *buf,
          int          count,
          MPI_Datatype type,
          int          dest,
          int          tag,
          MPI_Comm     comm)
{
  ++calls[f_Ssend];
  count_send(count, type, dest);
  TIMED(PMPI_Ssend(buf, count, type, dest, tag, comm));
}

int
MPI_Bsend(const void  *buf,
          int          count,
          MPI_Datatype type,
          int          dest,
          int          tag,
          MPI_Comm     comm)
{
  ++calls[f_Bsend];
  count_send(count, type, dest);
  TIMED(PMPI_Bsend(buf, count, type, dest, tag, comm));
}

int
MPI_Isend(const void  *buf,
          int          count,
          MPI_Datatype type,
          int          dest,
          int          tag,
          MPI_Comm     comm,
          MPI_Request *request)
{
  ++calls[f_Isend];
  count_send(count, type, dest);
  TIMED(PMPI_Isend(buf, count, type, dest, tag, comm, request));
}

int
MPI_Issend(const void  *buf,
           int          count,
           MPI_Datatype type,
           int          dest,
           int          tag,
           MPI_Comm     comm,
           MPI_Request *request)
{
  ++calls[f_Issend];
  count_send(count, type, dest);
  TIMED(PMPI_Issend(buf, count, type, dest, tag, comm, request));
}

int
MPI_Sendrecv(const void  *sendbuf,
             int          sendcount,
             MPI_Datatype sendtype,
             int          dest,
             int          sendtag,
             void        *recvbuf,
             int          recvcount,
             MPI_Datatype recvtype,
             int          source,
             int          recvtag,
             MPI_Comm     comm,
             MPI_Status  *status)
{
  ++calls[f_Sendrecv];
  count_send(sendcount, sendtype, dest);
  TIMED(PMPI_Sendrecv(sendbuf,
                      sendcount,
                      sendtype,
                      dest,
                      sendtag,
                      recvbuf,
                      recvcount,
                      recvtype,
                      source,
                      recvtag,
                      comm,
                      status));
}

/* Collectives. */
int
MPI_Barrier(MPI_Comm comm)
{
  ++calls[f_Barrier];
  count_collective(0);
  TIMED(PMPI_Barrier(comm));
}

int
MPI_Ibarrier(MPI_Comm comm, MPI_Request *request)
{
  ++calls[f_Ibarrier];
  count_collective(0);
  TIMED(PMPI_Ibarrier(comm, request));
}

int
MPI_Bcast(void *buf, int count, MPI_Datatype type, int root, MPI_Comm comm)
{
  ++calls[f_Bcast];
  count_collective(bytes_of(count, type));
  TIMED(PMPI_Bcast(buf, count, type, root, comm));
}

int
MPI_Allreduce(const void  *sendbuf,
              void        *recvbuf,
              int          count,
              MPI_Datatype type,
              MPI_Op       op,
              MPI_Comm     comm)
{
  ++calls[f_Allreduce];
  count_collective(bytes_of(count, type));
  TIMED(PMPI_Allreduce(sendbuf, recvbuf, count, type, op, comm));
}

int
MPI_Iallreduce(const void  *sendbuf,
               void        *recvbuf,
               int          count,
               MPI_Datatype type,
               MPI_Op       op,
               MPI_Comm     comm,
               MPI_Request *request)
{
  ++calls[f_Iallreduce];
  count_collective(bytes_of(count, type));
  TIMED(PMPI_Iallreduce(sendbuf, recvbuf, count, type, op, comm, request));
}

int
MPI_Reduce(const void  *sendbuf,
           void        *recvbuf,
           int          count,
           MPI_Datatype type,
           MPI_Op       op,
           int          root,
           MPI_Comm     comm)
{
  ++calls[f_Reduce];
  count_collective(bytes_of(count, type));
  TIMED(PMPI_Reduce(sendbuf, recvbuf, count, type, op, root, comm));
}

int
MPI_Scan(const void  *sendbuf,
         void        *recvbuf,
         int          count,
         MPI_Datatype type,
         MPI_Op       op,
         MPI_Comm     comm)
{
  ++calls[f_Scan];
  count_collective(bytes_of(count, type));
  TIMED(PMPI_Scan(sendbuf, recvbuf, count, type, op, comm));
}

int
MPI_Exscan(const void  *sendbuf,
           void        *recvbuf,
           int          count,
           MPI_Datatype type,
           MPI_Op       op,
           MPI_Comm     comm)
{
  ++calls[f_Exscan];
  count_collective(bytes_of(count, type));
  TIMED(PMPI_Exscan(sendbuf, recvbuf, count, type, op, comm));
}

int
MPI_Allgather(const void  *sendbuf,
              int          sendcount,
              MPI_Datatype sendtype,
              void        *recvbuf,
              int          recvcount,
              MPI_Datatype recvtype,
              MPI_Comm     comm)
{
  ++calls[f_Allgather];
  count_collective(bytes_of(sendcount, sendtype));
  TIMED(PMPI_Allgather(
    sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm));
}

int
MPI_Allgatherv(const void  *sendbuf,
               int          sendcount,
               MPI_Datatype sendtype,
               void        *recvbuf,
               const int   *recvcounts,
               const int   *displs,
               MPI_Datatype recvtype,
               MPI_Comm     comm)
{
  ++calls[f_Allgatherv];
  count_collective(bytes_of(sendcount, sendtype));
  TIMED(PMPI_Allgatherv(
    sendbuf, sendcount, sendtype, recvbuf, recvcounts, displs, recvtype, comm));
}

int
MPI_Gather(const void  *sendbuf,
           int          sendcount,
           MPI_Datatype sendtype,
           void        *recvbuf,
           int          recvcount,
           MPI_Datatype recvtype,
           int          root,
           MPI_Comm     comm)
{
  ++calls[f_Gather];
  count_collective(bytes_of(sendcount, sendtype));
  TIMED(PMPI_Gather(
    sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm));
}

int
MPI_Gatherv(const void  *sendbuf,
            int          sendcount,
            MPI_Datatype sendtype,
            void        *recvbuf,
            const int   *recvcounts,
            const int   *displs,
            MPI_Datatype recvtype,
            int          root,
            MPI_Comm     comm)
{
  ++calls[f_Gatherv];
  count_collective(bytes_of(sendcount, sendtype));
  TIMED(PMPI_Gatherv(sendbuf,
                     sendcount,
                     sendtype,
                     recvbuf,
                     recvcounts,
                     displs,
                     recvtype,
                     root,
                     comm));
}

int
MPI_Alltoall(const void  *sendbuf,
             int          sendcount,
             MPI_Datatype sendtype,
             void        *recvbuf,
             int          recvcount,
             MPI_Datatype recvtype,
             MPI_Comm     comm)
{
  ++calls[f_Alltoall];
  int size = 0;
  PMPI_Comm_size(comm, &size);
  count_collective((size - 1) * bytes_of(sendcount, sendtype));
  TIMED(PMPI_Alltoall(
    sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, comm));
}

int
MPI_Alltoallv(const void  *sendbuf,
              const int   *sendcounts,
              const int   *sdispls,
              MPI_Datatype sendtype,
              void        *recvbuf,
              const int   *recvcounts,
              const int   *rdispls,
              MPI_Datatype recvtype,
              MPI_Comm     comm)
{
  ++calls[f_Alltoallv];
  count_collective(sum_of_counts(sendcounts, sendtype, comm));
  TIMED(PMPI_Alltoallv(sendbuf,
                       sendcounts,
                       sdispls,
                       sendtype,
                       recvbuf,
                       recvcounts,
                       rdispls,
                       recvtype,
                       comm));
}

int
MPI_Reduce_scatter_block(const void  *sendbuf,
                         void        *recvbuf,
                         int          recvcount,
                         MPI_Datatype type,
                         MPI_Op       op,
                         MPI_Comm     comm)
{
  ++calls[f_Reduce_scatter_block];
  int size = 0;
  PMPI_Comm_size(comm, &size);
  count_collective(size * bytes_of(recvcount, type));
  TIMED(PMPI_Reduce_scatter_block(sendbuf, recvbuf, recvcount, type, op, comm));
}

int
MPI_Scatter(const void  *sendbuf,
            int          sendcount,
            MPI_Datatype sendtype,
            void        *recvbuf,
            int          recvcount,
            MPI_Datatype recvtype,
            int          root,
            MPI_Comm     comm)
{
  ++calls[f_Scatter];
  count_collective(bytes_of(recvcount, recvtype));
  TIMED(PMPI_Scatter(
    sendbuf, sendcount, sendtype, recvbuf, recvcount, recvtype, root, comm));
}

/* Receiving and waiting: timed only. */
int
MPI_Recv(void        *buf,
         int          count,
         MPI_Datatype type,
         int          source,
         int          tag,
         MPI_Comm     comm,
         MPI_Status  *status)
{
  ++calls[f_Recv];
  TIMED(PMPI_Recv(buf, count, type, source, tag, comm, status));
}

int
MPI_Probe(int source, int tag, MPI_Comm comm, MPI_Status *status)
{
  ++calls[f_Probe];
  TIMED(PMPI_Probe(source, tag, comm, status));
}

int
MPI_Iprobe(int source, int tag, MPI_Comm comm, int *flag, MPI_Status *status)
{
  ++calls[f_Iprobe];
  TIMED(PMPI_Iprobe(source, tag, comm, flag, status));
}

int
MPI_Wait(MPI_Request *request, MPI_Status *status)
{
  ++calls[f_Wait];
  TIMED(PMPI_Wait(request, status));
}

int
MPI_Waitall(int count, MPI_Request requests[], MPI_Status statuses[])
{
  ++calls[f_Waitall];
  TIMED(PMPI_Waitall(count, requests, statuses));
}

int
MPI_Waitany(int count, MPI_Request requests[], int *index, MPI_Status *status)
{
  ++calls[f_Waitany];
  TIMED(PMPI_Waitany(count, requests, index, status));
}

int
MPI_Waitsome(int         incount,
             MPI_Request requests[],
             int        *outcount,
             int         indices[],
             MPI_Status  statuses[])
{
  ++calls[f_Waitsome];
  TIMED(PMPI_Waitsome(incount, requests, outcount, indices, statuses));
}

int
MPI_Test(MPI_Request *request, int *flag, MPI_Status *status)
{
  ++calls[f_Test];
  TIMED(PMPI_Test(request, flag, status));
}

int
MPI_Testall(int count, MPI_Request requests[], int *flag, MPI_Status statuses[])
{
  ++calls[f_Testall];
  TIMED(PMPI_Testall(count, requests, flag, statuses));
}

int
MPI_Finalize(void)
{
  int rank = 0;
  PMPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const char *prefix = getenv("MPI_TRAFFIC_OUTPUT");
  char        name[4096];
  snprintf(
    name, sizeof(name), "%s.%d", prefix != NULL ? prefix : "mpi_traffic", rank);
  FILE *file = fopen(name, "w");
  if (file != NULL)
    {
      fprintf(file,
              "rank %d p2p_messages %lld p2p_bytes %lld collectives %lld "
              "collective_bytes %lld mpi_seconds %.6f\n",
              rank,
              p2p_messages,
              p2p_bytes,
              collectives,
              collective_bytes,
              mpi_seconds);
      fprintf(file, "calls");
      for (int f = 0; f < n_functions; ++f)
        if (calls[f] > 0)
          fprintf(file, " %s %lld", function_names[f], calls[f]);
      fprintf(file, "\n");
      fclose(file);
    }
  return PMPI_Finalize();
}
