// Output files: checked before the work, written atomically (temporary file + fsync + rename).
#include "lightsolver/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace lightsolver {
namespace {

namespace fs = std::filesystem;

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

std::string errno_text(int err) { return std::strerror(err); }

// The file actually replaced: a symbolic link's target (so the link survives), else the path.
fs::path resolve(const std::string& path) {
  const fs::path p(path);
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(p, ec))) {
    const fs::path target = fs::weakly_canonical(p, ec);
    if (!ec) return target;
  }
  return p;
}

fs::path folder_of(const fs::path& p) {
  return p.has_parent_path() ? p.parent_path() : fs::path(".");
}

// A fresh, exclusive temporary file next to `target`; the name starts with a dot and ends in
// ".tmp" so a listing shows what it is should a crash ever leave one behind.
int create_temporary(const fs::path& target, fs::path& tmp) {
  static std::atomic<unsigned> counter{0};
  for (int attempt = 0; attempt < 100; ++attempt) {
    tmp = folder_of(target) / ("." + target.filename().string() + "." + std::to_string(::getpid()) +
                               "." + std::to_string(counter++) + ".tmp");
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  errno = EEXIST;
  return -1;
}

// Reasons a path can never be written, found without touching the file system.
void check_path_shape(const fs::path& p, const std::string& what) {
  std::error_code ec;
  if (p.empty()) throw OutputError("the " + what + " path is empty");
  if (!p.has_filename() || fs::is_directory(p, ec)) {
    throw OutputError("cannot write the " + what + " " + quoted(p) + ": it is a folder");
  }
  const fs::file_status st = fs::status(p, ec);
  if (fs::exists(st) && !fs::is_regular_file(st)) {
    throw OutputError("cannot write the " + what + " " + quoted(p) +
                      ": it exists and is not a regular file");
  }
  const fs::path folder = folder_of(p);
  const fs::file_status fst = fs::status(folder, ec);
  if (!fs::exists(fst)) {
    throw OutputError("cannot write the " + what + " " + quoted(p) + ": the folder " +
                      quoted(folder) + " does not exist");
  }
  if (!fs::is_directory(fst)) {
    throw OutputError("cannot write the " + what + " " + quoted(p) + ": " + quoted(folder) +
                      " is not a folder");
  }
}

bool write_all(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

// A replaced file keeps its permissions (the temporary was created 0666 minus the umask).
void keep_mode(int fd, const fs::path& target) {
  struct stat st {};
  if (::stat(target.c_str(), &st) == 0) ::fchmod(fd, st.st_mode & 07777);
}

// Makes the rename itself durable; best effort (some file systems refuse fsync on folders).
void sync_folder(const fs::path& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

void check_writable(const std::string& path, const std::string& what) {
  const fs::path p = resolve(path);
  check_path_shape(p, what);
  fs::path tmp;
  const int fd = create_temporary(p, tmp);
  if (fd < 0) {
    throw OutputError("cannot write the " + what + " " + quoted(p) + ": cannot create files in " +
                      quoted(folder_of(p)) + " (" + errno_text(errno) + ")");
  }
  ::close(fd);
  ::unlink(tmp.c_str());
}

namespace {
std::atomic<bool> g_skip_writes{false};
}  // namespace

void skip_file_writes(bool skip) { g_skip_writes.store(skip); }

void write_file_atomically(const std::string& path, std::string_view bytes) {
  if (g_skip_writes.load()) return;
  const fs::path p = resolve(path);
  check_path_shape(p, "file");
  fs::path tmp;
  const int fd = create_temporary(p, tmp);
  if (fd < 0) {
    throw OutputError("cannot write " + quoted(p) + ": cannot create a temporary file in " +
                      quoted(folder_of(p)) + " (" + errno_text(errno) + ")");
  }
  keep_mode(fd, p);
  bool ok = write_all(fd, bytes) && ::fsync(fd) == 0;
  int err = ok ? 0 : errno;
  if (::close(fd) != 0 && ok) {
    ok = false;
    err = errno;
  }
  if (ok && ::rename(tmp.c_str(), p.c_str()) != 0) {
    ok = false;
    err = errno;
  }
  if (!ok) {
    ::unlink(tmp.c_str());
    throw OutputError("cannot write " + quoted(p) + " (" + errno_text(err) +
                      "); the previous file, if any, is unchanged");
  }
  sync_folder(folder_of(p));
}

}  // namespace lightsolver
