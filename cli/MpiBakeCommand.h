#pragma once
#include <CLI/CLI.hpp>

#include "cli/BakeOptions.h"
#include "formats/VolumeWriter.h"

namespace baker {

struct MpiPrinting {
  bool quiet = false, json = false;
  bool nonNegativeForFormat = false;  // the output's format asked for the fit >= 0
};

// `baker SCENE --mpi ...` in one rank of an mpirun job: bakes shard rank/size, and rank 0 writes
// `output` and prints the summary. A rank that fails prints its error and stops the whole job
// with its exit code; nothing is written.
int bakeOverMpi(const CLI::App& app, BakeOptions options, const VolumeOutput& output, const MpiPrinting& printing);

}  // namespace baker
