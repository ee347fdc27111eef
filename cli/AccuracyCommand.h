#pragma once

namespace baker {

// `baker accuracy SCENE --basis LIST --rays LIST [--bounces LIST] [--out DIR] [bake options]`:
// bakes every combination, times it, and measures the error of the reconstructed irradiance
// against a converged reference; writes CSV, JSON, an SVG plot of error against bake time and a
// Markdown summary.
int runAccuracyCommand(int argc, char** argv);

}  // namespace baker
