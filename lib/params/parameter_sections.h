// How a model's section of the parameter file is read and written, from its
// parameter table alone (params/parameter_file.h). Each built-in section is
// one file of params/ ending in DRIVEID_PARAMETER_SECTION(NAME) { return
// MakeSection(...); }, NAME listed in DRIVEID_PARAMETER_SECTIONS
// (lib/CMakeLists.txt) in the order the sections are written; a model
// outside lib/ (a test-only model, docs/adding-a-model.md) registers its own
// with one line:
//   const bool kRegistered =
//       (RegisterParameterSection(MakeSection(MyParameterTable, "docs: ...")), true);
#pragma once

#include <algorithm>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "core/errors.h"
#include "models/parameter_table.h"

namespace driveid {

class ParameterFile;  // params/parameter_file.h; complete where a section is made

namespace section_io {

/// "path:line:column" of a node (the path alone without a mark).
std::string Where(const std::string& path, const YAML::Node& node);
/// A parameter value: finite, 0 or 1e-100 <= |v| <= 1e100; InputError naming `name` else.
double ParseNumber(const std::string& path, const std::string& name, const YAML::Node& node);
/// A standard error: a number as above and >= 0 (`name` ends in ".std").
double ParseStandardError(const std::string& path, const std::string& name, const YAML::Node& node);
/// Refuses non-mappings, duplicate and non-scalar keys.
void CheckMapping(const std::string& path, const std::string& name, const YAML::Node& node);
/// A number as written (shortest round trip).
std::string Number(double value);
/// A name (a URDF's link or joint) as a YAML key or list item: plain for
/// letters, digits, '_', '-', '.', else double-quoted.
std::string YamlName(const std::string& name);
/// A scalar's text; InputError naming `name` else.
std::string ParseText(const std::string& path, const std::string& name, const YAML::Node& node);
/// The value if the reader will accept it; OutputError naming `name` else.
double Writable(const std::string& name, double value);
/// CheckMapping, and every key one of `known` (InputError naming it else).
void CheckKeys(const std::string& path, const std::string& name, const YAML::Node& node,
               const std::vector<std::string>& known);
/// A YAML double-quoted string: control characters and bytes that are not
/// UTF-8 (a file name may hold any bytes) escaped as \xNN.
std::string Quoted(const std::string& text);
/// Text for a comment: as is when printable ASCII, else Quoted (a unit read
/// from a log must not end the comment and start a key).
std::string Comment(const std::string& text);
/// A statistic to six digits (a std, an interval's end).
std::string Short(double value);

template <class Section, class Model>
std::string KnownKeys(const ParameterTable<Section, Model>& table, const std::vector<std::string>& extra) {
  std::string known;
  for (const auto& row : table) known += std::string(known.empty() ? "" : ", ") + row.spec.key;
  for (const auto& key : extra) known += ", " + key;
  return known;
}

// Parses the keys of a section into `out` by its table. Keys in `extra` are
// left to the caller (returned as nodes); every other key must be declared.
template <class Section, class Model>
std::vector<std::pair<std::string, YAML::Node>> ParseSection(const std::string& path, const std::string& section,
                                                             const YAML::Node& node,
                                                             const ParameterTable<Section, Model>& table,
                                                             const std::vector<std::string>& extra, Section& out) {
  CheckMapping(path, section, node);
  std::vector<std::pair<std::string, YAML::Node>> others;
  for (const auto& item : node) {
    const std::string key = item.first.Scalar();
    const auto* row = FindParameter(table, key);
    if (row == nullptr) {
      if (std::find(extra.begin(), extra.end(), key) == extra.end()) {
        throw InputError(fmt::format("{}: {}.{}: unknown key (known: {})", Where(path, item.first), section, key,
                                     KnownKeys(table, extra)));
      }
      others.emplace_back(key, item.second);
      continue;
    }
    if (item.second.IsNull()) continue;  // "key: " with no value = not given
    const std::string name = section + "." + key;
    const double value = ParseNumber(path, name, item.second);
    if (!row->spec.Admits(value)) {
      throw InputError(fmt::format("{}: {}: must be {} {}, got {} ({})", Where(path, item.second), name,
                                   row->spec.lower_exclusive ? ">" : ">=", row->spec.lower_bound, value,
                                   row->spec.Doc()));
    }
    SectionValue(*row, out) = value;
  }
  for (const auto& row : table) {
    if (row.spec.required && !SectionValue(row, out)) {
      throw InputError(fmt::format("{}: {}.{}: missing value ({})", Where(path, node), section, row.spec.key,
                                   row.spec.Doc()));
    }
  }
  return others;
}

// The values of a section, each with its symbol, description and unit
// (`unit_of`: the unit a section states for itself, e.g. a linear axis';
// else the table's).
template <class Values, class Model>
std::string FormatSection(const Values& values, const ParameterTable<Values, Model>& table, const std::string& indent,
                          const std::function<std::string(const ParameterSpec&)>& unit_of = {}) {
  std::string out;
  for (const auto& row : table) {
    const std::optional<double>& value = SectionValue(row, values);
    if (!value) continue;
    const std::string line = fmt::format(
        "{}{}: {}", indent, row.spec.key,
        Number(Writable(fmt::format("{}.{}", Values::kSectionName, row.spec.key), *value)));
    const std::string symbol = row.spec.symbol == std::string(row.spec.key) ? "" : std::string(row.spec.symbol) + ", ";
    const std::string doc = unit_of ? fmt::format("{} [{}]", row.spec.description, unit_of(row.spec)) : row.spec.Doc();
    out += fmt::format("{:<28} # {}{}\n", line, symbol, doc);
  }
  return out;
}

}  // namespace section_io

// How one model's section is read and written: everything but the extra
// keys comes from the model's parameter table.
struct SectionHandler {
  std::string name;
  std::function<bool(const ParameterFile&)> present;
  std::function<void(const std::string& path, const YAML::Node& node, ParameterFile& file)> parse;
  std::function<std::string(const ParameterFile& file)> format;
};

// A handler for the section of the table's section type (named by its
// kSectionName), read and written by `table`; `extra_keys` are left to `parse_extra` and written by
// `format_extra` (e.g. the robot's elbows, the C-drive's controller).
template <class T>
struct NotDeduced {
  using type = T;
};

template <class Section, class Model>
SectionHandler MakeSection(
    const ParameterTable<Section, Model>& (*table)(), const char* comment, std::vector<std::string> extra_keys = {},
    typename NotDeduced<std::function<void(const std::string&, const std::string&, const YAML::Node&, Section&,
                                           ParameterFile&)>>::type parse_extra = {},
    typename NotDeduced<std::function<std::string(const Section&, const ParameterFile&)>>::type format_extra = {},
    typename NotDeduced<std::function<std::string(const ParameterSpec&, const Section&)>>::type unit_of = {}) {
  const char* name = Section::kSectionName;
  SectionHandler handler;
  handler.name = name;
  // `file` is taken as auto: ParameterFile is complete only where a section is made.
  handler.present = [](const auto& file) { return file.template Find<Section>() != nullptr; };
  handler.parse = [=](const std::string& path, const YAML::Node& node, auto& file) {
    Section section{};
    for (const auto& [key, value] : section_io::ParseSection(path, name, node, table(), extra_keys, section)) {
      parse_extra(path, key, value, section, file);
    }
    file.Set(std::move(section));
  };
  handler.format = [=](const auto& file) {
    const Section& section = *file.template Find<Section>();
    std::function<std::string(const ParameterSpec&)> unit;
    if (unit_of) unit = [&](const ParameterSpec& spec) { return unit_of(spec, section); };
    std::string body = section_io::FormatSection(section, table(), "  ", unit);
    if (format_extra) body += format_extra(section, file);
    // A section with no value must still read back as a mapping.
    const std::string key = body.empty() ? fmt::format("{}: {{}}", name) : fmt::format("{}:", name);
    return fmt::format("{:<23}# {}\n", key, comment) + body;
  };
  return handler;
}

/// Adds a section to those every parameter file may hold (read, written,
/// named in messages); std::logic_error for a name that exists.
void RegisterParameterSection(SectionHandler handler);
/// The sections every parameter file may hold, in the order they are written.
const std::vector<SectionHandler>& ParameterSections();

/// Defines the section listed as `name` in DRIVEID_PARAMETER_SECTIONS.
#define DRIVEID_PARAMETER_SECTION(name) ::driveid::SectionHandler MakeParameterSection_##name()

}  // namespace driveid
