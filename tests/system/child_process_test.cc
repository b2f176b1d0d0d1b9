// Untrusted work in a child (system/child_process.h): its output comes back; an
// exit code, a signal, a hang past the deadline and output past the limit
// are reported as such, and the child is always reaped.
#include <string>

#include <catch2/catch.hpp>

#include <csignal>
#include <unistd.h>

#include "system/child_process.h"

namespace driveid {
namespace {

TEST_CASE("the child's output comes back; its exit code or its signal is reported") {
  const ChildOutcome ok = RunInChild([] { WriteAll(1, "hello\n", 6); }, {});
  CHECK(ok.started);
  CHECK(ok.exited);
  CHECK(ok.exit_code == 0);
  CHECK(ok.output == "hello\n");

  const ChildOutcome failed = RunInChild([] { ::_exit(3); }, {});
  CHECK(failed.exited);
  CHECK(failed.exit_code == 3);

  // (SIGKILL: the sanitizers catch SIGSEGV and exit instead)
  const ChildOutcome killed = RunInChild([] { ::raise(SIGKILL); }, {});
  CHECK_FALSE(killed.exited);
  CHECK(killed.signal == SIGKILL);
  CHECK_FALSE(killed.timed_out);
}

TEST_CASE("a child that hangs is killed at the deadline; one that writes too much at the limit") {
  ChildLimits limits;
  limits.seconds = 1;
  const ChildOutcome hung = RunInChild([] {
    for (;;) ::pause();
  }, limits);
  CHECK(hung.timed_out);
  CHECK_FALSE(hung.exited);

  limits.seconds = 20;
  limits.max_output_bytes = 1000;
  const ChildOutcome flood = RunInChild([] {
    const std::string block(4096, 'x');
    for (;;) WriteAll(1, block.data(), block.size());
  }, limits);
  CHECK_FALSE(flood.timed_out);
  CHECK(flood.output.size() > 1000);
  CHECK(flood.output.size() <= 1000 + (1 << 20));  // stops within a read or two past the limit
  CHECK_FALSE(flood.exited);
}

TEST_CASE("WriteAll writes everything through a pipe smaller than the data; false on a bad descriptor") {
  const std::string data(200000, 'y');  // larger than a pipe's buffer: short writes while the parent drains it
  const ChildOutcome echo = RunInChild([&] { WriteAll(1, data.data(), data.size()); }, {});
  CHECK(echo.output == data);
  CHECK_FALSE(WriteAll(-1, "x", 1));
}

}  // namespace
}  // namespace driveid
