#pragma once
// The analyses behind docs/accuracy.md's reading of the tables (sonarmap_accuracy_table --analysis):
// where the errors of the default pipeline come from, each measured against the simulator's truth
// or on the real logs.
#include <string>

namespace sonarmap::bench {

/// Per head, harbour scene: the detected leading edge minus the nearest surface within the
/// nominal (−3 dB) beam, p10 / p50 / p90 over the beams with an obstacle.
void printLeadingEdgeTable();

/// Per head, tank scene, default mapping: the median offset along the line of sight of the
/// occupied voxels by incidence angle on the walls, and the voxels near the tank's corners.
void printIncidenceTable();

/// Per head: soft targets, the harbour and open water at false-alarm probabilities 1e-6 (the
/// default), 1e-4 and 1e-3.
void printFalseAlarmTable();

/// How often the residual above the calibrated background reaches 6 … 16.9 dB: in the simulated
/// heads' open water, in the real logs' water (bins between the minimum range and 0.1 m before
/// each beam's obstacle), and for one-look speckle. `data_dir` holds the real logs.
void printNoiseTailTable(const std::string& data_dir);

}  // namespace sonarmap::bench
