#pragma once
// weft run --report: report.html in the run's folder — the scene's description, the command,
// a contact sheet of evenly spaced frames, the last frame, and inline-SVG plots of the largest
// strain, the energies and the simulation/render time per frame, from the rows stats.csv got.
// Links are relative (the folder can be moved).

#include <filesystem>
#include <string>
#include <vector>

#include "app/io/stats_csv.h"
#include "render/image.h"

namespace weft::app {

struct Scene;

// frame_0001.png, ... (four digits or more), the name weft run gives frame k (1-based).
std::string frame_file_name(int frame);

// `count` frame numbers spread evenly over 1..frames, first and last included (all of them
// when frames ≤ count), increasing.
std::vector<int> evenly_spaced_frames(int frames, int count);

// A contact sheet of frame_NNNN.png in `dir` for the given frame numbers, each labelled with its
// time (frame / fps), about `max_width_px` wide. Throws std::runtime_error naming a frame that
// cannot be read.
render::Image frame_contact_sheet(const std::filesystem::path& dir, const std::vector<int>& frames,
                                  double fps, int max_width_px = 960);

// Frames shown on the report's contact sheet.
constexpr int report_sheet_frames = 12;

// Writes dir/report.html and dir/report_sheet.png for a run whose frames 1..rows.size() are in
// `dir` (rows: one per written frame, in order). Returns the report's path. Throws
// std::runtime_error when a file cannot be read or written.
std::filesystem::path write_run_report(const std::filesystem::path& dir, const Scene& scene,
                                       const std::string& command_line,
                                       const std::vector<FrameStats>& rows);

}  // namespace weft::app
