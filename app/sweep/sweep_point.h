#pragma once
// One point of a sweep run alone — a Slurm array task, `weft sweep … --point K` — leaves its
// result in the sweep's folder for the collect job (`weft sweep … --collect`) to merge:
// DIR/points/run_K.txt (wall time, steps, time step, largest strain, diverged and why, each
// number exactly, as a C99 hex float) and DIR/points/run_K.npy (the last frame's positions,
// float64). The .txt is written last: a point without it has no result.

#include <cstddef>
#include <filesystem>

#include "app/sweep/sweep_merge.h"

namespace weft::app {

// DIR/points/run_K.txt for run number k (1-based, the row of sweep.csv).
std::filesystem::path sweep_point_file(const std::filesystem::path& dir, std::size_t k);

// Writes run k's result (each file atomically).
void write_sweep_point(const std::filesystem::path& dir, std::size_t k, const SweepRun& run);

// Reads run k's result into `run` (whose settings and scene are set; its mesh is rebuilt from
// the scene). Throws std::runtime_error naming the file when there is none, it is damaged, or it
// is another sweep's (other settings).
void read_sweep_point(const std::filesystem::path& dir, std::size_t k, SweepRun& run);

}  // namespace weft::app
