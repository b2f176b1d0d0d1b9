#include "common/in_process.h"

#include "common/command_registry.h"

namespace driveid::cli {

InProcessResult RunInProcess(const std::string& tool, const std::vector<std::string>& args,
                             const std::string& command_line, const std::vector<GivenLog>& given,
                             const std::function<void(const std::string&)>& err) {
  InProcessResult result;
  StreamCapture capture;
  capture.err = err;
  const auto fail = [&](int code, const std::string& message) {
    result.code = code;
    result.message = Printable(ShowFlags(message));
  };
  {
    const CaptureStreams capturing(capture);
    const GivenLogsScope logs(given);
    CLI::App app{"driveid " DRIVEID_VERSION, tool};
    app.require_subcommand(1);
    const auto run = SetupCommand(app, tool, args);
    OneValuePerFlag(app);
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
    try {
      app.parse(reversed);
      run(command_line);
    } catch (const CLI::CallForHelp&) {
      capture.out += app.help();
    } catch (const CLI::ParseError& e) {
      fail(kUsage, std::string(e.what()) + " (see --help)");
    } catch (...) {  // GateFailed is not a std::exception
      const Refusal refusal = CurrentRefusal();
      fail(refusal.code, refusal.message);
      result.parameters = refusal.parameters;
    }
  }
  result.out = std::move(capture.out);
  result.fits = std::move(capture.fits);
  return result;
}

}  // namespace driveid::cli
