#include "params/parameter_file.h"

#include <algorithm>
#include <string_view>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "core/errors.h"
#include "params/feedback_section.h"
#include "params/feedforward_section.h"
#include "params/fit_section_yaml.h"
#include "params/parameter_sections.h"
#include "system/file_reading.h"

namespace driveid {
namespace {

using namespace section_io;

constexpr std::size_t kMaxParameterFileBytes = 1 << 20, kMaxParameterLineBytes = 1 << 16;  // what the reader accepts

std::string SectionNames() {
  std::vector<std::string> names;
  for (const auto& section : ParameterSections()) names.push_back(section.name);
  return fmt::format("{}", fmt::join(names, ", "));
}

// yaml-cpp parses nested collections recursively: refuse input that could
// exhaust the stack before handing it over (no real parameter file nests
// deeper than three levels).
void CheckNesting(const std::string& path, const std::string& text) {
  constexpr std::size_t kMaxBytes = 1 << 20;
  constexpr int kMaxFlowDepth = 32;
  constexpr std::size_t kMaxIndent = 64;
  if (text.size() > kMaxBytes) throw InputError(fmt::format("{}: parameter file larger than {} bytes", path, kMaxBytes));
  int depth = 0, line = 1;
  std::size_t indent = 0;
  bool at_line_start = true;
  for (char c : text) {
    if (c == '\n') {
      ++line;
      indent = 0;
      at_line_start = true;
      continue;
    }
    if (at_line_start && (c == ' ' || c == '-' || c == '\t')) {
      if (++indent > kMaxIndent) {
        throw InputError(fmt::format("{}:{}: nested deeper than a parameter file can be (indent over {})", path, line,
                                     kMaxIndent));
      }
      continue;
    }
    at_line_start = false;
    if (c == '[' || c == '{') {
      if (++depth > kMaxFlowDepth) {
        throw InputError(fmt::format("{}:{}: nested deeper than a parameter file can be (over {} brackets)", path,
                                     line, kMaxFlowDepth));
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
}

// What ReadParameterFile accepts (1 MiB, lines of 64 KiB): else nothing is written.
void RequireReadable(const std::string& out) {
  if (out.size() > kMaxParameterFileBytes) {
    throw OutputError(fmt::format("the parameter file would be {} bytes, a parameter file holds at most {}; nothing "
                                  "written",
                                  out.size(), kMaxParameterFileBytes));
  }
  for (std::size_t begin = 0, line = 1; begin < out.size(); ++line) {
    const std::size_t end = std::min(out.find('\n', begin), out.size());
    if (end - begin > kMaxParameterLineBytes) {
      throw OutputError(fmt::format("line {} of the parameter file would be {} bytes (\"{}...\"), at most {}; nothing "
                                    "written",
                                    line, end - begin, out.substr(begin, 40), kMaxParameterLineBytes));
    }
    begin = end + 1;
  }
}

}  // namespace

ParameterFile ParseParameterFile(const std::string& path, const std::string& text) {
  CheckNesting(path, text);
  // YAML::Load reads the first document only: refuse a second one, marked by
  // a line "---" (or "...") after content. (YAML::LoadAll can loop on
  // hostile input, so the markers are found here.)
  {
    bool content = false;
    int line = 0;
    for (std::size_t begin = 0; begin < text.size();) {
      const std::size_t end = std::min(text.find('\n', begin), text.size());
      const std::string_view row(text.data() + begin, end - begin);
      ++line;
      const bool marker = (row.rfind("---", 0) == 0 || row.rfind("...", 0) == 0) &&
                          (row.size() == 3 || row[3] == ' ' || row[3] == '\t' || row[3] == '\r');
      if (marker && content) {
        throw InputError(fmt::format("{}:{}: a second YAML document: a parameter file holds one", path, line));
      }
      const std::size_t first = row.find_first_not_of(" \t\r");
      if (!marker && first != std::string_view::npos && row[first] != '#') content = true;
      begin = end + 1;
    }
  }
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(fmt::format("{}:{}:{}: invalid YAML: {}", path, e.mark.line + 1, e.mark.column + 1, e.msg));
  } catch (const YAML::Exception& e) {
    throw InputError(fmt::format("{}: invalid YAML: {}", path, e.msg));
  }
  if (root.IsNull()) throw InputError(fmt::format("{}: empty parameter file", path));
  CheckMapping(path, "parameter file", root);
  ParameterFile file;
  for (const auto& item : root) {
    const std::string section = item.first.Scalar();
    const SectionHandler* handler = nullptr;
    for (const auto& candidate : ParameterSections()) {
      if (candidate.name == section) handler = &candidate;
    }
    if (handler != nullptr) {
      handler->parse(path, item.second, file);
    } else if (section == "feedforward") {
      file.feedforward = ParseFeedforward(path, item.second);
    } else if (section == "feedback") {
      file.feedback = ParseFeedbackSection(path, item.second);
    } else if (section == "fit") {
      PreviousFit fit = ParseFitSection(path, item.second);
      file.had_fit_section = true;
      file.fit_estimates = std::move(fit.estimates);
      file.fit_rmse = std::move(fit.rmse);
      file.fit_inflation = std::move(fit.inflation);
      file.fit_correlations = std::move(fit.correlations);
    } else {
      throw InputError(fmt::format("{}: {}: unknown section (known: {}, feedforward, feedback, fit)", Where(path, item.first), section,
                                   SectionNames()));
    }
  }
  if (file.had_fit_section) file.fit_text = FitSectionText(text, root);
  bool any_model = false;
  for (const auto& section : ParameterSections()) any_model = any_model || section.present(file);
  if (!any_model && file.feedback.empty()) throw InputError(fmt::format("{}: no model section ({})", path, SectionNames()));
  return file;
}

ParameterFile ReadParameterFile(const std::string& path) {
  ReadLimits limits;
  limits.max_bytes = kMaxParameterFileBytes;
  limits.max_line_bytes = kMaxParameterLineBytes;
  limits.max_bytes_hint = "a parameter file may be at most 1 MiB";
  return ParseParameterFile(path, ReadFileToString(path, limits));
}

std::string FormatParameterFile(const ParameterFile& file, const FitResult* fit, const FitProvenance* provenance,
                                const std::vector<DerivedQuantity>& derived) {
  std::string out = "# driveid parameter file (docs/formats.md). Units: SI, radians.\n";
  for (const auto& section : ParameterSections()) {
    if (section.present(file)) out += section.format(file);
  }
  if (!file.feedforward.gains.empty()) out += FormatFeedforward(file.feedforward);
  if (!file.feedback.empty()) out += FormatFeedbackSection(file.feedback);
  if (fit == nullptr && provenance == nullptr) out += file.fit_text;
  if (fit != nullptr && provenance != nullptr) {
    out += FormatFitSection(*fit, *provenance, derived);
  }
  RequireReadable(out);
  return out;
}

}  // namespace driveid
