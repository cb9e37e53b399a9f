// weft run's checkpoint file (see run_checkpoint.h).
//
// Layout: the magic line "weft checkpoint 3\n" (version 2: the simulator's state begins with its
// mesh section, the remeshed cloth's mesh; version 1 had none; version 3: the payload's hash and
// the "inputs" section), the build hash, the scene text's hash and the payload's hash (FNV-1a of
// every byte after the header; 8 bytes each, native order), then the payload, the sections of a
// sim::StateWriter: "run" (frame, interval, scene source and text), "inputs" (each input file's
// path and the hash of its bytes), "rows", "crossings", "simulator" (Simulator::save_state's
// bytes) and "end".

#include "app/io/run_checkpoint.h"

#include <elf.h>
#include <link.h>

#include <cstdio>
#include <algorithm>
#include <cstring>
#include <fstream>
#include <sstream>
#include <type_traits>

#include "app/io/output_files.h"
#include "app/io/input_error.h"
#include "base/atomic_file.h"
#include "base/file_read.h"
#include "sim/state_archive.h"

namespace weft::app {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kMagicPrefix = "weft checkpoint ";
constexpr int kCheckpointVersion = 3;
const std::string kMagic = std::string(kMagicPrefix) + std::to_string(kCheckpointVersion) + "\n";

std::string read_bytes(const fs::path& path, std::uint64_t max_bytes, const std::string& what) {
  try {
    return base::read_file_capped(path, max_bytes, what);
  } catch (const base::FileReadError& e) {
    throw InputError(e.what());
  }
}

std::string hex(std::uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

// The GNU build ID note of the main program (its first loaded object), or "" without one.
std::string gnu_build_id() {
  std::string id;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* out) -> int {
        for (int i = 0; i < info->dlpi_phnum; ++i) {
          const ElfW(Phdr)& segment = info->dlpi_phdr[i];
          if (segment.p_type != PT_NOTE) continue;
          const char* p = reinterpret_cast<const char*>(info->dlpi_addr + segment.p_vaddr);
          const char* const end = p + segment.p_memsz;
          const auto align4 = [](size_t n) { return (n + 3) & ~size_t{3}; };
          while (p + sizeof(ElfW(Nhdr)) <= end) {
            const auto* note = reinterpret_cast<const ElfW(Nhdr)*>(p);
            const char* name = p + sizeof(ElfW(Nhdr));
            const char* desc = name + align4(note->n_namesz);
            if (desc + note->n_descsz > end) break;
            if (note->n_type == NT_GNU_BUILD_ID && note->n_namesz == 4 &&
                std::memcmp(name, "GNU", 4) == 0) {
              static_cast<std::string*>(out)->assign(desc, note->n_descsz);
              return 1;
            }
            p = desc + align4(note->n_descsz);
          }
        }
        return 1;  // the main program only
      },
      &id);
  return id;
}

}  // namespace

std::uint64_t fnv1a_64(std::string_view bytes) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

std::uint64_t build_hash() {
  static const std::uint64_t hash = [] {
    const std::string id = gnu_build_id();
    return fnv1a_64(id.empty() ? read_bytes("/proc/self/exe", std::uint64_t{1} << 34, "weft's program")
                               : id);
  }();
  return hash;
}

void write_checkpoint(const fs::path& dir, const RunCheckpoint& c) {
  static_assert(std::is_trivially_copyable_v<FrameStats>, "stats rows are saved as bytes");
  sim::StateWriter out;
  out.section("run");
  out.pod(c.frame);
  out.pod(c.every);
  out.text(c.scene_source);
  out.text(c.scene_text);
  out.section("inputs");
  out.pod(static_cast<std::uint64_t>(c.inputs.size()));
  for (const InputFileHash& input : c.inputs) {
    out.text(input.path);
    out.pod(input.hash);
  }
  out.section("rows");
  out.pods(c.rows);
  out.section("crossings");
  out.pods(c.crossing_frames);
  out.section("simulator");
  out.text(c.simulator_state);
  out.section("end");
  base::write_file_atomically(dir / checkpoint_file_name,
                              checkpoint_header(fnv1a_64(c.scene_text), out.bytes()) + out.bytes());
}

RunCheckpoint read_checkpoint(const fs::path& dir) {
  const fs::path path = fs::is_directory(dir) ? dir / checkpoint_file_name : dir;
  return parse_checkpoint(read_bytes(path, max_checkpoint_bytes, "a checkpoint"), path.string());
}

std::string checkpoint_header(std::uint64_t scene_hash, std::string_view payload) {
  std::string bytes(kMagic);
  const std::uint64_t hashes[3] = {build_hash(), scene_hash, fnv1a_64(payload)};
  bytes.append(reinterpret_cast<const char*>(hashes), sizeof hashes);
  return bytes;
}

RunCheckpoint parse_checkpoint(const std::string& bytes, const std::string& name) {
  std::uint64_t hashes[3];
  if (bytes.compare(0, kMagicPrefix.size(), kMagicPrefix) == 0 &&
      bytes.compare(0, kMagic.size(), kMagic) != 0) {
    const std::size_t end = bytes.find('\n', kMagicPrefix.size());
    const std::string version =
        bytes.substr(kMagicPrefix.size(), std::min<std::size_t>(end, 40) - kMagicPrefix.size());
    throw InputError(name + ": a weft checkpoint of format version " + version + "; this weft "
                     "reads version " + std::to_string(kCheckpointVersion) + " only (rerun the "
                     "scene from the start)");
  }
  if (bytes.compare(0, kMagic.size(), kMagic) != 0 || bytes.size() < kMagic.size() + sizeof hashes)
    throw InputError(name + ": not a weft checkpoint (weft run --checkpoint-every writes them)");
  std::memcpy(hashes, bytes.data() + kMagic.size(), sizeof hashes);
  if (hashes[0] != build_hash())
    throw InputError(name + ": written by another build of weft (build " + hex(hashes[0]) +
                     ", this one " + hex(build_hash()) +
                     "): a checkpoint resumes only with the executable that wrote it; rerun "
                     "the scene from the start");
  const std::string_view payload = std::string_view(bytes).substr(kMagic.size() + sizeof hashes);
  if (fnv1a_64(payload) != hashes[2])
    throw InputError(name + ": its content does not match the hash in its header (a damaged "
                     "checkpoint: a byte changed, or the file was cut short)");
  RunCheckpoint c;
  try {
    sim::StateReader in(payload, name);
    in.section("run");
    in.pod(c.frame);
    in.pod(c.every);
    c.scene_source = in.text();
    c.scene_text = in.text();
    in.section("inputs");
    std::uint64_t inputs = 0;
    in.pod(inputs);
    for (std::uint64_t k = 0; k < inputs && k < max_scene_inputs; ++k) {
      InputFileHash input;
      input.path = in.text();
      in.pod(input.hash);
      c.inputs.push_back(std::move(input));
    }
    if (inputs > max_scene_inputs) in.fail("too many input files");
    in.section("rows");
    in.pods(c.rows);
    in.section("crossings");
    in.pods(c.crossing_frames);
    in.section("simulator");
    c.simulator_state = in.text();
    in.section("end");
    if (!in.at_end()) in.fail("bytes after the end");
  } catch (const sim::StateArchiveError& e) {
    throw InputError(std::string(e.what()) + " (a damaged checkpoint)");
  }
  if (fnv1a_64(c.scene_text) != hashes[1])
    throw InputError(name + ": the scene it holds does not match its hash (a damaged checkpoint)");
  if (c.frame < 1 || c.rows.size() != static_cast<std::size_t>(c.frame))
    throw InputError(name + ": " + std::to_string(c.rows.size()) + " stats rows for frame " +
                     std::to_string(c.frame) + " (a damaged checkpoint)");
  return c;
}

std::vector<InputFileHash> hash_input_files(const std::vector<fs::path>& files) {
  std::vector<InputFileHash> out;
  for (const fs::path& file : files)
    out.push_back({file.string(), fnv1a_64(read_bytes(file, max_checkpoint_bytes, "an input file"))});
  return out;
}

void check_input_files(const RunCheckpoint& checkpoint, const std::vector<fs::path>& files,
                       const std::string& checkpoint_name) {
  const std::vector<InputFileHash> now = hash_input_files(files);
  if (now.size() != checkpoint.inputs.size())
    throw InputError(checkpoint_name + ": the checkpoint's scene read " +
                     std::to_string(checkpoint.inputs.size()) + " input files, the scene now " +
                     std::to_string(now.size()) + " (a damaged checkpoint)");
  for (std::size_t k = 0; k < now.size(); ++k)
    if (now[k].hash != checkpoint.inputs[k].hash)
      throw InputError(now[k].path + ": not the file the checkpointed run read (" +
                       checkpoint.inputs[k].path + ", hash " + hex(checkpoint.inputs[k].hash) +
                       "; this one " + hex(now[k].hash) + "): it changed, or the run is resumed "
                       "from another folder; restore it, or rerun the scene from the start");
}

}  // namespace weft::app
