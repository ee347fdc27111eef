#pragma once

namespace baker {

// `baker validate REFERENCE NEW [--tolerance X] [--report FILE.json] [--junit FILE.xml] [--json]`
// compares two volumes (either format, any bases, possibly different grids) in reconstructed
// irradiance at the reference's probes; `baker validate VOLUME --against-reference DIR ...`
// compares a volume with reference_probe.py's panoramas. Exit 0 when every check passes, 1 when
// one fails (irradiance beyond the tolerance, a probe whose validity changed, adaptive volumes on
// the same grids placing other probes), 2 for unusable input (unreadable files, grids that do not
// overlap). Adaptive volumes are compared at every probe of every level of the reference.
//
// Report keys (--report, --json), both modes: mode ("volume" or "reference"), reference, new,
// error_definition, normals, floor, tolerance, passed, max_relative_error, mean_relative_error,
// p99_relative_error, level (mean over probes of the reference's mean irradiance), error_of_level
// {mean, p99, max} (each probe's largest |E_new(n) - E_ref(n)| over normals and RGB / level; null
// when the reference is black),
// probes_compared, probes_outside_new_grid, worst_probes [{adaptive_level, index, position,
// relative_error, max_abs_error, reference_mean_irradiance}; against a reference also file, and
// index is the probe's number in probes.json instead of [i, j, k], without adaptive_level],
// validity_compared, validity_changes [{adaptive_level, index, position, reference, new}],
// sky_visibility_max_abs_difference (null when not compared), metadata_differences [{field,
// reference, new}], checks [{name, passed, skipped, message}]; volume mode also grids_match
// (every level's grid the same) and placement_changes ({reference_only, new_only}: probes one
// adaptive volume holds and the other does not; null unless both are adaptive on the same grids),
// reference mode also note. adaptive_level is the probe's level in an adaptive volume (0 for a
// uniform one); the top-level `level` is an irradiance.
// argv[0] is "validate".
int runValidateCommand(int argc, char** argv);

}  // namespace baker
