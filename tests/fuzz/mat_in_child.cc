// Linked into every fuzzer: a MAT file (whichever reader meets one) is read
// in the forked child by the reader linked here (logs/formats/mat_reader.h), not by
// the reader process: an exec per input would slow the fuzzers tenfold.
// The child has the limits of the reader process (logs/formats/mat_source.cc).
#include <string>

#include "logs/formats/mat_source.h"
#include "logs/formats/mat_reader.h"
#include "logs/table_source.h"

namespace {

bool ReadMatInChild(int fd, const std::string& path, const std::string& file) {
  return driveid::WriteMatReaderReply(fd, driveid::MatReaderReply(path, file));
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  driveid::ReadMatFilesInForkedChild(ReadMatInChild);
  return 0;
}
