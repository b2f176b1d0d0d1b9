// driveid-mat-reader PATH FILE: reads the MAT file FILE (the tools' copy of
// the log PATH, named in messages) and writes the reply of io/mat_reply.h
// to standard output. Started by the MAT source (lib/io/mat_source.cc) with
// its address space and time capped; not meant to be run by hand.
#include <string>

#include "io/mat_reader.h"
#include "io/mat_reply.h"

int main(int argc, char** argv) {
  const std::string reply =
      argc == 3 ? driveid::MatReaderReply(argv[1], argv[2])
                : driveid::SerialiseMatError("usage: driveid-mat-reader PATH FILE (started by the driveid tools)");
  return driveid::WriteMatReaderReply(1, reply) ? 0 : 1;
}
