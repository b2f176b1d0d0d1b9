// Untrusted work in a child process: a library that trusts the sizes a file
// claims (matio, HDF5) or that ends the process on an error (MuJoCo's
// mju_error) runs in a forked child, so that a hostile file can cost the
// child, never the tool. The child dies with the tool (PR_SET_PDEATHSIG,
// and the tools' signal handlers kill it: system/temporary_files.h), its address
// space is capped where no sanitizer needs it, and its time is limited.
// What it writes to its standard output comes back to the parent.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

namespace driveid {

struct ChildLimits {
  long seconds = 5;                        ///< killed after this long
  double address_space_bytes = 0.0;        ///< RLIMIT_AS of the child (0: none; never under ASan)
  std::size_t max_output_bytes = 1 << 30;  ///< reading stops beyond this
};

struct ChildOutcome {
  std::string output;      ///< what the child wrote to its standard output
  bool started = false;    ///< fork and pipe succeeded
  bool timed_out = false;  ///< killed after ChildLimits::seconds
  bool exited = false;     ///< exited normally (else: a signal)
  int exit_code = 0;       ///< when exited
  int signal = 0;          ///< when killed by a signal
};

/// Forks; the child runs `body` with its standard output on a pipe to the
/// parent, then _exit(0) (body may exec or _exit itself). The parent reads
/// until the child closes the pipe, the output limit or the deadline, and
/// reaps the child. Never throws; the caller words the errors.
ChildOutcome RunInChild(const std::function<void()>& body, const ChildLimits& limits);

/// Writes all of `bytes` to `fd` (retrying short writes and EINTR); false on
/// an error. Async-signal-safe, for children and error handlers.
bool WriteAll(int fd, const char* bytes, std::size_t size) noexcept;

}  // namespace driveid
