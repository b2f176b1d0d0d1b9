#include "logs/paired_source.h"

#include <utility>

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {
namespace {

class JoinedSource : public PairedSource {
 public:
  JoinedSource(std::unique_ptr<TableSource> a, std::unique_ptr<TableSource> b) : PairedSource(std::move(a), std::move(b)) {
    const auto la = a_->column_lengths(), lb = b_->column_lengths();
    const std::size_t rows_a = la.empty() ? 0 : la.front(), rows_b = lb.empty() ? 0 : lb.front();
    if (rows_a != rows_b) {
      throw InputError(fmt::format("{}: {} rows, but {} (joined with ‹join›) has {}: a joined file must have one row "
                                   "per row of the log",
                                   a_->path(), rows_a, b_->path(), rows_b));
    }
  }
  std::vector<std::size_t> column_lengths() const override {
    auto lengths = a_->column_lengths();
    for (auto n : b_->column_lengths()) lengths.push_back(n);
    return lengths;
  }
  std::vector<std::string> notes() const override {
    auto notes = a_->notes();
    notes.push_back("joined row by row with " + b_->path());
    for (const auto& n : b_->notes()) notes.push_back(b_->path() + ": " + n);
    return notes;
  }
  TableData Read(const std::vector<std::size_t>& columns) const override {
    std::vector<std::size_t> in_a, in_b;
    Split(columns, in_a, in_b);
    TableData da = a_->Read(in_a), db = b_->Read(in_b);
    TableData out;
    out.line_numbers = !da.line_numbers.empty() ? std::move(da.line_numbers) : std::move(db.line_numbers);
    std::size_t ia = 0, ib = 0;
    for (auto c : columns) out.columns.push_back(InA(c) ? std::move(da.columns[ia++]) : std::move(db.columns[ib++]));
    return out;
  }
};

}  // namespace

std::unique_ptr<TableSource> JoinSources(std::unique_ptr<TableSource> first, std::unique_ptr<TableSource> second) {
  return std::make_unique<JoinedSource>(std::move(first), std::move(second));
}

}  // namespace driveid
