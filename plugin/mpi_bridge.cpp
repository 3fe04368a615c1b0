// mpi_bridge: the MPI MUMPS and the few MPI calls the suite's plugins need under FreeFem++-mpi,
// in a library of their own that plugin/mpi_bridge.hpp opens in its own symbol scope. Built by
// `make` with mpicxx against Debian's MPI MUMPS (libmumps-dev) and OpenMPI (libopenmpi-dev); not a
// FreeFEM plugin (FreeFEM never loads it itself).
//
// Why a library of its own: FreeFEM's ff-Ipopt brings Debian's sequential MUMPS, whose
// libdmumps_seq exports the same dmumps_c as the MPI libdmumps, and whose libmpiseq exports stub
// MPI_Init, MPI_Comm_rank and the Fortran mpi_* calls. Linked into a plugin, whichever library the
// process loaded first would answer every call of both. Opened with dlopen(RTLD_LOCAL |
// RTLD_DEEPBIND), this library and its dependencies (libdmumps, libmumps_common, libmpi_mpifh,
// ScaLAPACK) look their symbols up among themselves first, and add none to the process's global
// scope, where IPOPT's sequential MUMPS keeps finding its own.
//
//   mpiBridgeMumps(id): the MPI dmumps_c on a DMUMPS_STRUC_C (the same header, dmumps_c.h, for both
//     builds); returns INFOG(1).
//   mpiBridgeMumpsSingle(id): the MPI smumps_c (single precision) on an SMUMPS_STRUC_C.
//   mpiBridgeBroadcast(data, n): n doubles from process 0 to every process.
//   mpiBridgeGather(value, all): every process's value, in rank order, on every process.
//   mpiBridgeBarrier(): every process waits for the others.
//   mpiBridgeProcesses(): the processes in MPI_COMM_WORLD (MUMPS's communicator here).
#include <mpi.h>
#include <dmumps_c.h>
#include <smumps_c.h>
#include <climits>

extern "C" {

int mpiBridgeMumps(void *id) {
  DMUMPS_STRUC_C *mumps = static_cast<DMUMPS_STRUC_C *>(id);
  dmumps_c(mumps);
  return mumps->infog[0];
}

int mpiBridgeMumpsSingle(void *id) {
  SMUMPS_STRUC_C *mumps = static_cast<SMUMPS_STRUC_C *>(id);
  smumps_c(mumps);
  return mumps->infog[0];
}

void mpiBridgeBroadcast(double *data, long n) {
  for (long first = 0; first < n; first += INT_MAX) {   // MPI counts are ints
    long count = n - first < INT_MAX ? n - first : INT_MAX;
    MPI_Bcast(data + first, int(count), MPI_DOUBLE, 0, MPI_COMM_WORLD);
  }
}

void mpiBridgeGather(double value, double *all) {
  MPI_Allgather(&value, 1, MPI_DOUBLE, all, 1, MPI_DOUBLE, MPI_COMM_WORLD);
}

void mpiBridgeBarrier() { MPI_Barrier(MPI_COMM_WORLD); }

int mpiBridgeProcesses() {
  int size = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

}
