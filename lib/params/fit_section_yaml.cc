#include "params/fit_section_yaml.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <set>
#include <string_view>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/estimate_record.h"
#include "core/fit_section.h"
#include "params/parameter_sections.h"

namespace driveid {
namespace {

using namespace section_io;

// Provenance text (the command line, notes) is information, not data: cut
// beyond `limit` bytes, saying so, so that a line stays within what the
// reader accepts (64 KiB).
constexpr std::size_t kMaxProvenanceText = 4096;
std::string Abbreviated(const std::string& text, std::size_t limit) {
  if (text.size() <= limit) return text;
  std::size_t cut = limit;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // not inside a UTF-8 character
  return fmt::format("{} ... ({} bytes in all)", text.substr(0, cut), text.size());
}


// An estimate record (core/estimate_record.h) as a YAML flow map,
// "{value: V, std: S, ci95: [L, H]}": the value to the last bit, the rest
// to six digits; `path` names it in messages (fit.estimates.NAME).
struct YamlRecordWriter {
  std::string path, out;
  void Next() { out += out.empty() ? "{" : ", "; }
  void Scalar(const char* key, EstimateField field, const double& v) {
    Next();
    out += field == EstimateField::kValue ? fmt::format("{}: {}", key, Number(Writable(path, v)))
                                          : fmt::format("{}: {}", key, Short(Writable(path + "." + key, v)));
  }
  void Interval(const char* key, const double& low, const double& high) {
    Next();
    const std::string name = path + "." + key;
    out += fmt::format("{}: [{}, {}]", key, Short(Writable(name, low)), Short(Writable(name, high)));
  }
  std::string Close() const { return out + "}"; }
};

// An estimate record read back from its YAML node `node` (`name`:
// fit.estimates.NAME): the scalars required, a standard error >= 0, the
// interval optional and ordered.
struct YamlRecordReader {
  const std::string& path;
  const std::string& name;
  const YAML::Node& node;
  void RequireScalars() const {
    struct Scalars {
      std::vector<std::string> keys;
      void Scalar(const char* key, EstimateField, const double&) { keys.emplace_back(key); }
      void Interval(const char*, const double&, const double&) {}
    } scalars;
    const ParameterEstimate none;
    VisitEstimateRecord(scalars, none);
    for (const auto& key : scalars.keys) {
      if (!node[key]) {
        throw InputError(fmt::format("{}: {}: needs a {}", Where(path, node), name, fmt::join(scalars.keys, " and a ")));
      }
    }
  }
  void Scalar(const char* key, EstimateField field, double& v) const {
    const std::string where = name + "." + key;
    v = field == EstimateField::kValue ? ParseNumber(path, where, node[key]) : ParseStandardError(path, where, node[key]);
  }
  void Interval(const char* key, double& low, double& high) const {
    const YAML::Node interval = node[key];
    if (!interval || !interval.IsSequence() || interval.size() != 2) return;
    low = ParseNumber(path, name + "." + key, interval[0]);
    high = ParseNumber(path, name + "." + key, interval[1]);
    if (low > high) {
      throw InputError(fmt::format("{}: {}.{} = [{}, {}]: the low end lies above the high end", Where(path, interval), name,
                                   key, low, high));
    }
  }
};




// fit.correlation as written (FormatCorrelation): a row per estimate, or a
// list of [name, name, r] for many parameters. Read for propagating a
// derived value's std (e.g. feedback gains from Kv and Ka).
void ParseFitCorrelation(const std::string& path, const YAML::Node& node, PreviousFit& file) {
  if (!node) return;
  const auto value = [&](const YAML::Node& n) {
    const double r = ParseNumber(path, "fit.correlation", n);
    if (std::abs(r) > 1.0 + 1e-9) throw InputError(fmt::format("{}: fit.correlation: {} is outside [-1, 1]", Where(path, n), r));
    return r;
  };
  if (node.IsMap()) {
    std::vector<std::string> names;
    for (const auto& row : node) names.push_back(row.first.Scalar());
    for (const auto& row : node) {
      if (!row.second.IsSequence() || row.second.size() != names.size()) {
        throw InputError(fmt::format("{}: fit.correlation.{}: expected {} numbers", Where(path, row.second),
                                     row.first.Scalar(), names.size()));
      }
      for (std::size_t j = 0; j < names.size(); ++j) {
        file.correlations.push_back({{row.first.Scalar(), names[j]}, value(row.second[j])});
      }
    }
  } else if (node.IsSequence()) {
    for (const auto& pair : node) {
      if (!pair.IsSequence() || pair.size() != 3 || !pair[0].IsScalar() || !pair[1].IsScalar()) {
        throw InputError(fmt::format("{}: fit.correlation: expected [name, name, r]", Where(path, pair)));
      }
      file.correlations.push_back({{pair[0].Scalar(), pair[1].Scalar()}, value(pair[2])});
    }
  } else {
    throw InputError(fmt::format("{}: fit.correlation: expected rows or pairs", Where(path, node)));
  }
}


}  // namespace

// The text of the top-level section `fit` as written: from the line of its
// key (at column 0) to the line of the next top-level key (the parser's
// marks, so that flow content at column 0 stays in), or to the end. "" when
// that text does not read back alone as the one section `fit` (e.g. a flow
// style document), and the section is then written anew or not at all.
std::string FitSectionText(const std::string& text, const YAML::Node& root) {
  int first = -1, next = -1;
  for (const auto& item : root) {
    const YAML::Mark mark = item.first.Mark();
    if (item.first.Scalar() == "fit") first = mark.column == 0 ? mark.line : -2;
  }
  if (first < 0) return "";
  for (const auto& item : root) {
    const int line = item.first.Mark().line;
    if (line > first && (next < 0 || line < next)) next = line;
    if (line == first && item.first.Scalar() != "fit") return "";
  }
  std::string block;
  int line = 0;
  for (std::size_t begin = 0; begin < text.size(); ++line) {
    const std::size_t end = std::min(text.find('\n', begin), text.size());
    if (line >= first && (next < 0 || line < next)) block.append(text, begin, end - begin).push_back('\n');
    begin = end + 1;
  }
  try {
    const YAML::Node alone = YAML::Load(block);
    if (!alone.IsMap() || alone.size() != 1 || !alone["fit"]) return "";
  } catch (const YAML::Exception&) {
    return "";
  }
  return block;
}

// The fit section of an earlier fit: its keys checked, its estimates and
// correlations read, its text kept.
PreviousFit ParseFitSection(const std::string& path, const YAML::Node& node) {
  PreviousFit file;
  // Provenance of an earlier fit: accepted so that a fit's output is a
  // valid input; replaced by a new fit, kept by a writer that fits nothing.
  CheckMapping(path, "fit", node);
  std::vector<std::string> known;
  for (const FitKey key : kFitSectionKeys) known.emplace_back(FitKeyName(key));
  for (const auto& entry : node) {
    const std::string key = entry.first.Scalar();
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      throw InputError(fmt::format("{}: fit.{}: unknown key (the fit section is written by the tools; known: {})",
                                   Where(path, entry.first), key, fmt::join(known, ", ")));
    }
  }
  const YAML::Node data = node[FitKeyName(FitKey::kData)];
  if (data && data.IsSequence()) {
    for (const auto& record : data) {
      CheckKeys(path, "fit.data", record, {kFitDataKeys.begin(), kFitDataKeys.end()});
    }
  }
  const YAML::Node derived = node[FitKeyName(FitKey::kDerived)];
  if (derived && derived.IsMap()) {
    for (const auto& entry : derived) {
      CheckKeys(path, "fit.derived." + entry.first.Scalar(), entry.second, {kFitDerivedKeys.begin(), kFitDerivedKeys.end()});
    }
  }
  const YAML::Node estimates = node[FitKeyName(FitKey::kEstimates)];
  if (estimates && estimates.IsMap()) {
    for (const auto& entry : estimates) {
      const YAML::Node& e = entry.second;
      const std::string name = "fit.estimates." + entry.first.Scalar();
      CheckKeys(path, name, e, EstimateRecordKeys());
      ParameterEstimate estimate;
      estimate.name = entry.first.Scalar();
      YamlRecordReader reader{path, name, e};
      reader.RequireScalars();
      VisitEstimateRecord(reader, estimate);
      file.estimates.push_back(estimate);
    }
  }
  ParseFitCorrelation(path, node[FitKeyName(FitKey::kCorrelation)], file);
  for (auto [key, into] : {std::pair{FitKeyName(FitKey::kRmse), &file.rmse},
                           std::pair{FitKeyName(FitKey::kInflation), &file.inflation}}) {
    const YAML::Node channels = node[key];
    if (!channels || !channels.IsMap()) continue;
    for (const auto& entry : channels) {
      // Read for a design's noise only: a value that is no number is left out.
      if (!entry.first.IsScalar() || !entry.second.IsScalar()) continue;
      try {
        into->emplace_back(entry.first.Scalar(), ParseNumber(path, "fit." + std::string(key), entry.second));
      } catch (const InputError&) {
      }
    }
  }
  return file;
}


namespace {

// The fit section's data records.
std::string FormatDataRecords(const FitProvenance& provenance) {
  std::string out;
  for (const auto& record : provenance.data) {
    out += fmt::format("    - {{file: {}, sha256: {}, samples: {}", Quoted(record.file), record.sha256,
                       record.samples);
    if (!record.segment.empty()) out += fmt::format(", segment: {}", Quoted(record.segment));
    if (!record.notes.empty()) {
      std::vector<std::string> quoted;
      for (const auto& note : record.notes) quoted.push_back(Quoted(Abbreviated(note, kMaxProvenanceText / 4)));
      out += fmt::format(", notes: [{}]", fmt::join(quoted, ", "));
    }
    out += "}\n";
  }
  return out;
}

// The correlation matrix, or its strongest pairs for many parameters.
std::string FormatCorrelation(const FitResult* fit) {
  std::string out;
  const std::size_t p = fit->estimates.size();
  if (p <= kFullCorrelationParameters) {
    out += "\n";
    for (std::size_t i = 0; i < p; ++i) {
      out += fmt::format("    {}: [", fit->estimates[i].name);
      for (std::size_t j = 0; j < p; ++j) out += fmt::format("{}{:.4f}", j ? ", " : "", fit->correlation[i * p + j]);
      out += "]\n";
    }
  } else {
    // The matrix grows with the square of the parameters (a fit of 1000
    // logs with offsets: 8 MB): the strongest pairs (the matrix: --json).
    out += fmt::format("  # {} parameters: the {} strongest pairs (docs/formats.md)\n", p, kFullCorrelationParameters);
    for (const auto& pair : StrongestCorrelations(*fit, kFullCorrelationParameters)) {
      out += fmt::format("    - [{}, {}, {:.4f}]\n", fit->estimates[pair.first].name, fit->estimates[pair.second].name,
                         pair.correlation);
    }
  }
  return out;
}

// One key of the fit section (core/fit_section.h), its lines indented
// under "fit:"; model and derived only when there are any.
std::string FormatFitKey(FitKey key, const FitResult& fit, const FitProvenance& provenance,
                         const std::vector<DerivedQuantity>& derived) {
  const std::string name = FitKeyName(key);
  std::string out;
  switch (key) {
    case FitKey::kCommand:
      return fmt::format("  {}: {}\n", name, Quoted(Abbreviated(provenance.command, kMaxProvenanceText)));
    case FitKey::kVersion:
      return fmt::format("  {}: {}\n", name, Quoted(provenance.version));
    case FitKey::kModel:
      return provenance.model.empty() ? "" : fmt::format("  {}: {}\n", name, provenance.model);
    case FitKey::kData:
      return "  " + name + ":\n" + FormatDataRecords(provenance);
    case FitKey::kEstimates:
      out = "  " + name + ":\n";
      for (const auto& e : fit.estimates) {
        for (double v : {e.value, e.standard_error, e.ci95_low, e.ci95_high}) {
          if (!std::isfinite(v)) {
            throw OutputError(fmt::format("fit.estimates.{}: not finite ({} +- {}); nothing written", e.name, e.value,
                                          e.standard_error));
          }
        }
        YamlRecordWriter writer{"fit.estimates." + e.name, ""};
        VisitEstimateRecord(writer, e);
        out += fmt::format("    {}: {}{}\n", e.name, writer.Close(), e.unit.empty() ? "" : "  # " + Comment(e.unit));
      }
      return out;
    case FitKey::kDerived:
      if (derived.empty()) return "";
      out = "  " + name + ":\n";
      for (const auto& d : derived) {
        out += fmt::format("    {}: {{value: {}, std: {}}}  # {}\n", d.name,
                           Number(Writable("fit.derived." + d.name, d.value)),
                           Short(Writable("fit.derived." + d.name + ".std", d.standard_error)), Comment(d.unit));
      }
      return out;
    case FitKey::kCorrelation:
      return "  " + name + ":" + FormatCorrelation(&fit);
    case FitKey::kRmse:
      out = "  " + name + ":\n";
      for (const auto& c : fit.channels) out += fmt::format("    {}: {}\n", Quoted(c.name), Short(c.rmse));
      return out;
    case FitKey::kFitPercent:
      out = "  " + name + ":\n";
      for (const auto& c : fit.channels) {
        out += std::isnan(c.fit_percent)
                   ? fmt::format("    {}: null  # the channel (nearly) does not vary: docs/models.md#adequacy\n",
                                 Quoted(c.name))
                   : fmt::format("    {}: {:.3f}\n", Quoted(c.name), c.fit_percent);
      }
      return out;
    case FitKey::kAutocorrelation:
      out = "  " + name + ":  # residual lag-1, per channel\n";
      for (const auto& c : fit.channels) out += fmt::format("    {}: {:.4f}\n", Quoted(c.name), c.autocorrelation);
      return out;
    case FitKey::kInflation:
      out = "  " + name + ":  # std with / without the correlation of the residuals (docs/models.md#identification)\n";
      for (const auto& c : fit.channels) out += fmt::format("    {}: {:.4f}\n", Quoted(c.name), c.inflation);
      return out;
    case FitKey::kSingularValues:
      out = "  " + name + ": [";
      for (std::size_t i = 0; i < fit.singular_values.size(); ++i) {
        out += fmt::format("{}{:.4g}", i ? ", " : "", fit.singular_values[i]);
      }
      return out + "]\n";
    case FitKey::kIterations:
      return fmt::format("  {}: {}\n", name, fit.iterations);
    case FitKey::kConverged:
      return fmt::format("  {}: {}\n", name, fit.converged ? "true" : "false");
  }
  return out;
}

}  // namespace

std::string FormatFitSection(const FitResult& fit, const FitProvenance& provenance,
                             const std::vector<DerivedQuantity>& derived) {
  std::string out = "fit:\n";
  for (const FitKey key : kFitSectionKeys) out += FormatFitKey(key, fit, provenance, derived);
  return out;
}

}  // namespace driveid
