// driveid-mat-reader PATH FILE: reads the MAT file FILE (the tools' copy of
// the log PATH, named in messages) and writes the reply of logs/formats/mat_reply.h
// to standard output. Started by the MAT source (lib/logs/formats/mat_source.cc) with
// its address space and time capped; not meant to be run by hand.
#include <csignal>
#include <string>

#include <unistd.h>

#include <sys/prctl.h>

#include "logs/formats/mat_reader.h"
#include "logs/formats/mat_reply.h"

namespace {

// A v7.3 file is read from a named copy (logs/formats/mat_reader.h): every signal
// that can end this process and can be caught removes it first. The tool's
// death arrives as SIGTERM (not the SIGKILL RunInChild asks for), and the
// tool's deadline sends SIGTERM before SIGKILL.
void RemoveCopyAndDie(int signal_number) {
  driveid::RemoveMatReaderCopyNow();
  ::signal(signal_number, SIG_DFL);
  ::raise(signal_number);
}

void RemoveCopyOnSignals() {
  for (int s : {SIGTERM, SIGINT, SIGHUP, SIGPIPE, SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL, SIGXCPU, SIGXFSZ}) {
    ::signal(s, RemoveCopyAndDie);
  }
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  if (::getppid() == 1) ::raise(SIGTERM);  // the tool died before the line above
}

}  // namespace

int main(int argc, char** argv) {
  RemoveCopyOnSignals();
  const std::string reply =
      argc == 3 ? driveid::MatReaderReply(argv[1], argv[2])
                : driveid::SerialiseMatError("usage: driveid-mat-reader PATH FILE (started by the driveid tools)");
  return driveid::WriteMatReaderReply(1, reply) ? 0 : 1;
}
