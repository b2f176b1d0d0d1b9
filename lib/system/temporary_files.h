// Temporary files of a run (staged outputs, gnuplot's script and image) and
// the child process writing one, kept where a signal handler can reach them:
// on SIGINT/SIGTERM/SIGHUP/SIGPIPE the tools remove them before they die
// (docs/validation.md, "Robustness and the error bars"). The library installs no handler;
// the applications call RemoveTemporaryFilesNow() from theirs.
#pragma once

#include <string>

#include <signal.h>
#include <sys/types.h>

namespace driveid {

/// Creates a file from a mkstemps pattern ("...XXXXXX" followed by
/// `suffix_length` characters; the X's are replaced in place) and
/// registers it, with the termination signals blocked in between so that no
/// signal can leave it behind. Returns the open descriptor, or -1 (errno set).
int CreateTemporaryFile(std::string& pattern, int suffix_length = 0);

/// Creates a file without a name (O_TMPFILE in the temporary folder, else a
/// memfd), open for reading and writing, close-on-exec: nothing is left
/// behind whatever ends the process, and nothing needs removing. A child
/// reaches it as /proc/self/fd/N once the flag is cleared for it. Returns
/// the descriptor, or -1 (errno set).
int CreateUnnamedFile();

/// Forgets a temporary file (after it was renamed into place or removed).
void ForgetTemporaryFile(const std::string& path);

/// Removes a temporary file and forgets it.
void RemoveTemporaryFile(const std::string& path);

/// The child process writing into temporary files (0: none); killed and
/// reaped by RemoveTemporaryFilesNow().
void SetTemporaryFileWriter(pid_t child);

/// Async-signal-safe: ends the registered child (SIGTERM, SIGKILL after a
/// second) and reaps it, and unlinks every registered
/// temporary file. For signal handlers only.
void RemoveTemporaryFilesNow() noexcept;

/// Blocks SIGINT, SIGTERM, SIGHUP and SIGPIPE while alive (e.g. during a commit of
/// several outputs, so that a signal cannot leave some committed and some
/// not); a signal that arrives meanwhile is delivered at the end.
class TerminationSignalsBlocked {
 public:
  TerminationSignalsBlocked();
  ~TerminationSignalsBlocked();
  TerminationSignalsBlocked(const TerminationSignalsBlocked&) = delete;
  TerminationSignalsBlocked& operator=(const TerminationSignalsBlocked&) = delete;

 private:
  sigset_t saved_;
};

}  // namespace driveid
