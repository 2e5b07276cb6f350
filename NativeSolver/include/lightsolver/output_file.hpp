#pragma once
/// \file output_file.hpp
/// Output files that are never lost: every path is checked before any work starts, and every
/// file is written atomically (a temporary file in the same folder, flushed and synced, then
/// renamed over the target), so a failed or killed write leaves the previous file intact.

#include <stdexcept>
#include <string>
#include <string_view>

namespace lightsolver {

/// A file that cannot be written (missing folder, a folder as target, no permission, disk
/// full). The message names the file and what it is for.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Checks, before any work, that `path` can be written: its folder exists and new files can be
/// created in it (tested by creating and removing a temporary file there, so read-only mounts
/// and permissions are seen as they are), and the path is not a folder or another non-regular
/// file. An existing regular file may be replaced. `what` names the file in the message (e.g.
/// "results file"). Throws OutputError.
void check_writable(const std::string& path, const std::string& what);

/// Writes `bytes` to `path` atomically: a temporary file in the same folder is written,
/// flushed, fsync'ed and renamed over `path` (a symbolic link is followed: its target is
/// replaced). On any failure the temporary file is removed, the previous file stays as it was,
/// and OutputError names the path. New files get the usual permissions (0666 minus the umask);
/// a replaced file keeps its permissions.
void write_file_atomically(const std::string& path, std::string_view bytes);

/// Makes write_file_atomically() write nothing (true) or write again (false). Under mpirun only
/// rank 0 writes the files of a run that every process computed (docs/cluster.md); the others'
/// check_writable() still checks, so a bad path fails on every process before any work.
void skip_file_writes(bool skip);

}  // namespace lightsolver
