#pragma once

namespace baker {

// `baker merge OUT PART...`: the parts of a bake cut into shards, as the one volume a single
// process would have written (formats/PartMerge.h).
int runMergeCommand(int argc, char** argv);

}  // namespace baker
