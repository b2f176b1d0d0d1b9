#include "logs/axis_reference.h"

#include <fmt/format.h>

#include "core/errors.h"
#include "logs/column_expression.h"
#include "logs/log_input.h"
#include "logs/log_columns.h"

namespace driveid {
namespace {
using R = AxisReference;
constexpr LogColumn<R> kColumns[] = {
    RequiredColumn<R>("t", &FieldOf<R, &R::time>, "{}"),
    RequiredColumn<R>("q", &FieldOf<R, &R::position>, "{:.12g}"),
    {"qd", true, &FieldOf<R, &R::rate>, "{:.12g}"},
    {"qdd", true, &FieldOf<R, &R::acceleration>, "{:.12g}"},
};

}  // namespace

AxisReference ReadAxisReference(const std::string& path) {
  CsvLog csv = ReadCsvLog(path, LogColumnRequest(kColumns));
  if (csv.rows() < 3) throw InputError(fmt::format("{}: {} rows: a reference needs at least 3", path, csv.rows()));
  AxisReference r = MakeLogFromColumns(kColumns, csv);
  // Central differences on the sample times (column_expression.h's derivative).
  if (r.rate.empty()) ApplyColumnOperation("derivative", r.time, r.rate = r.position);
  if (r.acceleration.empty()) ApplyColumnOperation("derivative", r.time, r.acceleration = r.rate);
  return r;
}

std::string FormatAxisReference(const AxisReference& reference, const std::vector<std::string>& comments) {
  return FormatLogColumns(kColumns, reference, comments);
}

}  // namespace driveid
