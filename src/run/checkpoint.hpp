// Checkpoint files of a run (`dspdem run --checkpoint-every T`, a stop signal, `--restart`).
//
// One file, <run folder>/checkpoint.bin: a magic line, a header (which build and which case
// wrote it, and where the run was), the state (core/archive.hpp), and a CRC-32 of all of it.
// It is written to a temporary name, flushed to disk and renamed over the previous one, so
// the last good checkpoint survives a crash at any moment. A restart checks the build and
// the case (its resolved text) before it builds anything, and the model's sizes before it
// loads: a checkpoint of another case or build is refused with the reason.
//
// A distributed run (mpirun -n N) writes one file per process at the same step: process 0
// checkpoint.bin, process r checkpoint.<r>.bin beside it, each with its share's state; a
// restart needs the same N (the partition is the same: METIS with a fixed seed).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/archive.hpp"
#include "core/types.hpp"

namespace dspdem {

struct CheckpointHeader {
  // 14: the CRC-32s of series.csv and fragments.csv as far as the checkpoint's run had written them; 13: a joint
  // point's last slip and friction on its face's frame (the friction a vector), the extrinsic offsets' slip
  // on that frame; 12: the touches' contact points and weights in the contacts' history (a successor takes a spring
  // over); 11: the integrator's last step, the kick's term at the start and the damping's lag (the ledger), a joint
  // point's shear dropped by a forced break; 10: the touches' cluster shares in the contacts' history; 9: the
  // executable and the wall-time interval (8: the contacts' pairs first found overlapping; 7: no previous fragment ids
  // in the contacts' state; 6: no largest slip in the joints' states; 5: the contacts' spring energies; 4: the
  // integrator's step; 3: processes and rank; 2: the deepest contact)
  int format = 14;
  std::string build;  ///< dspdem version, commit, compiler and build type
  /// executable_id() of what wrote it: `report --resume` continues a killed run's checkpoint
  /// only if this executable wrote it, as it keeps a finished run only if its summary says so.
  std::string executable;
  std::string case_path;          ///< absolute path of the case file
  std::vector<std::string> sets;  ///< the run's --set overrides
  std::string resolved_toml;      ///< the case with every default filled in, as run
  Index nodes = 0, elements = 0, joints = 0;
  Real dt = 0;
  long steps = 0;  ///< where the run was
  Real time = 0;
  Real checkpoint_every = 0;    ///< the run's interval [s] (0: signals only)
  double checkpoint_wall = 0;   ///< and by wall time [s] (0: never); a restart keeps both
  int processes = 1, rank = 0;  ///< a distributed run's: how many wrote, and which one this is

  template <class Ar>
  void persist(Ar& ar) {
    ar(format, build, executable, case_path, sets, resolved_toml, nodes, elements, joints, dt, steps, time,
       checkpoint_every, checkpoint_wall, processes, rank);
  }
};

/// Process `rank`'s file of the checkpoint whose process-0 file is `path`.
std::string checkpoint_piece(const std::string& path, int rank);

/// CRC-32 of the first `bytes` bytes of file `path` (all of it with bytes = -1), and how many
/// it read: fewer than asked when the file is shorter (or missing: 0). Given `so_far`, the
/// CRC of the file's first so_far.bytes bytes, only the bytes after them are read: a growing
/// file's CRC at each checkpoint costs what it grew by, not its length (a file now shorter
/// than so_far.bytes, or a so_far longer than `bytes`, is read from its start).
struct FileCrc {
  std::uint32_t crc = 0;
  std::uint64_t bytes = 0;
};
FileCrc file_crc(const std::string& path, std::uint64_t bytes = static_cast<std::uint64_t>(-1), FileCrc so_far = {});

/// This build's identity, as written into checkpoints.
std::string checkpoint_build_id();

/// This executable: checkpoint_build_id and the CRC-32 of the executable's own file
/// (/proc/self/exe). The commit in the build id is the last one that changed the code
/// (cmake/commit_id.cmake), "-dirty" for uncommitted changes to it; the file's CRC tells
/// two dirty builds apart. Written into summary.json.
std::string executable_id();

/// Writes header then body (the archive's bytes) to path atomically: to path.tmp, flushed
/// to disk, then renamed over path; with into_place = false the rename is left to
/// move_checkpoint_into_place (a distributed run renames every process's file only once all
/// are written, so that a crash leaves the old set or the new one, short of the renames).
void write_checkpoint(const std::string& path, const CheckpointHeader& h, const StateArchive& body,
                      bool into_place = true);
void move_checkpoint_into_place(const std::string& path);

/// Reads and checks (magic, CRC, format, build) a checkpoint; returns its header and leaves
/// `body` positioned at the state.
CheckpointHeader read_checkpoint(const std::string& path, StateArchive& body);

/// Error unless `h`, the header of checkpoint `path`, was written by this build (another build
/// may round differently or store its state differently: no bitwise restart).
void require_this_build(const CheckpointHeader& h, const std::string& path);

/// A checkpoint file found and read whole once, its magic, CRC and format checked (not its
/// build: require_this_build), with its header.
struct FoundCheckpoint {
  std::string path;
  CheckpointHeader header;
};

/// The newest checkpoint (the last written) a run folder holds: its own checkpoint.bin, an
/// interrupted run's (interrupted_run/) or a killed run's (.staging-*/). Error if none. The
/// last written, not the furthest: a killed run's staging folder can outlive it, and a
/// later run of the folder, of another case perhaps, is the one to go on with.
FoundCheckpoint find_checkpoint(const std::string& run_dir);

/// The checkpoint files in `run_dir` that `run --restart` could go on from and that a run
/// finishing there would remove: an interrupted run's (interrupted_run/) and killed runs'
/// (.staging-*/ whose process is gone). Not read: a damaged one is still someone's hours.
std::vector<std::string> checkpoints_left(const std::string& run_dir);

/// What `dspdem run --restart PATH` goes on from: a run folder's newest checkpoint
/// (find_checkpoint), or the checkpoint file PATH itself, which must be process 0's (a
/// distributed run's other files are found beside it) and, in a staging folder, a killed
/// run's, not a live one's (as find_checkpoint). A file names one checkpoint exactly:
/// `report --resume` hands its child the one it judged, which a second search of the folder
/// might not find again.
FoundCheckpoint restart_checkpoint(const std::string& path);

/// The run folder a checkpoint file belongs to, where a restart writes by default: the folder
/// that holds it, or that folder's when it lies in interrupted_run/ or a .staging-* folder; as
/// an absolute path, without '.' or '..'.
std::string run_folder_of(const std::string& checkpoint_file);

/// The first line where two case texts differ, for messages ("" if equal).
std::string first_difference(const std::string& a, const std::string& b);

/// The case file as a resolved case text names it in its first comment ("" if it has none).
std::string case_origin(const std::string& resolved);

/// Whether two resolved case texts are the same case: equal but for their first comment,
/// which names the file as it was given (`cases/x.toml` at the start; the absolute path the
/// checkpoint keeps when a restart reads the case again).
bool same_case(const std::string& a, const std::string& b);

}  // namespace dspdem
