#pragma once
// What a Slurm task asks for (`--cpus-per-task`, `--mem`, `--time`), estimated from the work:
// vertices × simulation steps (steps that solve a linear system cost more), frames drawn ×
// pixels (× samples for the ray tracer). The model
// and how its constants were measured are in docs/cluster.md ("Resource estimates"); it is
// deliberately generous (a task killed at its limit costs more than an idle reservation).

#include <string>
#include <vector>

namespace weft::app {

struct Scene;

struct SlurmResources {
  int cpus = 1;
  long memory_mb = 0;    // 0: not asked (the cluster's default)
  int time_minutes = 0;  // 0: not asked
  std::string basis;     // how they were estimated, written into the script as a comment
};

// One task's work.
struct TaskWork {
  long vertices = 0;        // the cloth's
  long steps = 0;           // simulation steps (0: no simulation, e.g. weft render)
  bool solves = false;      // each step solves a linear system (implicit Euler, projection)
  long frames_drawn = 0;    // images written
  long pixels = 0;          // per image
  int samples = 0;          // ray tracer's samples per pixel; 0: the rasterizer
};

// The work of drawing `frames` of the scene's images (no simulation, no vertices counted).
TaskWork drawing_work(const Scene& scene, long frames);

// The work of simulating the scene's frames (and drawing them, if `draws`). Builds the scene's
// simulator to count its vertices and steps (no step is taken).
TaskWork scene_work(const Scene& scene, bool draws);

// Estimated single-CPU seconds and megabytes of one task (docs/cluster.md's model).
double estimated_seconds(const TaskWork& work);
double estimated_megabytes(const TaskWork& work);

// What to ask for to run every one of `works` (the largest of each): the time limit is
// kTimeMargin × the estimate plus kStartMinutes, in whole minutes, and memory is kMemoryMargin ×
// the estimate, rounded up to 64 MB. `cpus` is what the task's --threads uses; the estimate does
// not count on them (a slower node, a busy file system).
SlurmResources estimate_resources(const std::vector<TaskWork>& works, int cpus);

// Slurm's time format for a limit in minutes: "MM" below an hour, else "D-HH:MM:00".
std::string slurm_time(int minutes);

}  // namespace weft::app
