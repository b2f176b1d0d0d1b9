#include "system/atomic_file.h"

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "core/errors.h"
#include "system/temporary_files.h"

namespace driveid {
namespace {

// Writes all of `contents` to `fd`; false (errno set) on failure.
bool WriteAll(int fd, const std::string& contents) {
  const char* data = contents.data();
  std::size_t left = contents.size();
  while (left > 0) {
    const ssize_t written = ::write(fd, data, left);
    if (written < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data += written;
    left -= static_cast<std::size_t>(written);
  }
  return true;
}

[[noreturn]] void Fail(const std::string& path, const char* what, int error) {
  throw OutputError(fmt::format("{}: {}: {}", path, what, std::strerror(error)));
}

// A device, FIFO or socket is written in place: it is never replaced by a
// regular file (as root, renaming over /dev/null would replace it). A FIFO
// without a reader is an error, not a hang.
void WriteInPlace(const std::string& path, const std::string& contents) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) Fail(path, "cannot open output", errno);
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  const bool written = WriteAll(fd, contents);
  const int error = errno;
  const bool closed = ::close(fd) == 0;
  if (!written) Fail(path, "cannot write output", error);
  if (!closed) Fail(path, "cannot write output", errno);
}

// The staging file's mkstemp pattern beside `destination`: its name with
// ".tmp.XXXXXX" appended, the name cut short where that would pass the
// file system's limit on a name (NAME_MAX), so that an output name of up to
// that limit can be staged.
std::string StagingPattern(const std::string& destination) {
  static const std::string suffix = ".tmp.XXXXXX";
  const std::size_t slash = destination.rfind('/');
  const std::size_t name_start = slash == std::string::npos ? 0 : slash + 1;
  std::string folder = destination.substr(0, name_start);
  std::string name = destination.substr(name_start);
  if (name.size() + suffix.size() > NAME_MAX) name.resize(NAME_MAX - suffix.size());
  return folder + name + suffix;
}

mode_t CurrentUmask() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return mask;
}

}  // namespace

namespace {

// One output on its way: where it goes and, for a regular file, the
// temporary file that holds it until the commit.
struct StagedOutput {
  std::string path;         // as given (for messages)
  std::string destination;  // the link's target for a symbolic link
  std::string temporary;    // "" for a device or FIFO (written in place at the commit)
  const std::string* contents = nullptr;
};

StagedOutput Stage(const std::string& path, const std::string& contents) {
  StagedOutput out{path, path, "", &contents};
  // A symbolic link is written through: its target is replaced, the link stays.
  struct stat link_status {};
  if (::lstat(path.c_str(), &link_status) == 0 && S_ISLNK(link_status.st_mode)) {
    std::vector<char> resolved(PATH_MAX + 1, '\0');
    if (::realpath(path.c_str(), resolved.data()) == nullptr) Fail(path, "cannot follow the link", errno);
    out.destination = resolved.data();
  }
  struct stat status {};
  mode_t mode = 0666 & ~CurrentUmask();
  if (::stat(out.destination.c_str(), &status) == 0) {
    if (S_ISDIR(status.st_mode)) throw OutputError(fmt::format("{}: is a directory", path));
    if (!S_ISREG(status.st_mode)) return out;  // device, FIFO, socket: in place
    if ((status.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0) {
      throw OutputError(fmt::format("{}: the file is read-only; not replaced", path));
    }
    mode = status.st_mode & 07777;  // an existing file keeps its permissions
  }
  std::string name = StagingPattern(out.destination);
  const int fd = CreateTemporaryFile(name);
  if (fd < 0) Fail(path, "cannot create output file", errno);
  out.temporary = name;
  bool ok = WriteAll(fd, contents);
  int error = errno;
  if (ok && (::fchmod(fd, mode) != 0 || ::fsync(fd) != 0)) {
    ok = false;
    error = errno;
  }
  if (::close(fd) != 0 && ok) {
    ok = false;
    error = errno;
  }
  if (!ok) {
    RemoveTemporaryFile(out.temporary);
    Fail(path, "cannot write output file", error);
  }
  return out;
}

}  // namespace

void WriteFilesAtomically(const std::vector<std::pair<std::string, std::string>>& files,
                          const std::function<void()>& before_commit) {
  std::vector<StagedOutput> staged;
  try {
    for (const auto& [path, contents] : files) staged.push_back(Stage(path, contents));
    // What can still fail and cannot be undone (devices, FIFOs, the caller's
    // standard output) goes first; a failure there leaves every file as it was.
    for (const auto& s : staged) {
      if (s.temporary.empty()) WriteInPlace(s.destination, *s.contents);
    }
    if (before_commit) before_commit();
    // Now replace the files, with the termination signals held back so that
    // a signal commits all or none.
    TerminationSignalsBlocked blocked;
    for (auto& s : staged) {
      if (s.temporary.empty()) continue;
      if (::rename(s.temporary.c_str(), s.destination.c_str()) != 0) {
        Fail(s.path, "cannot write output file", errno);  // the rest is discarded below
      }
      ForgetTemporaryFile(s.temporary);
      s.temporary.clear();
    }
  } catch (...) {
    for (const auto& s : staged) {
      if (!s.temporary.empty()) RemoveTemporaryFile(s.temporary);
    }
    throw;
  }
}

void WriteFileAtomically(const std::string& path, const std::string& contents) {
  WriteFilesAtomically({{path, contents}});
}

}  // namespace driveid
