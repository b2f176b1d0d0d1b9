// The input layer (docs/formats.md#logs): header-less and other-delimiter
// CSV, column expressions, --rate, crops, joins, MAT v5 and v7.3 files
// written here with matio, WPILib SysId JSON; values and error messages.
#include "logs/formats/mat_source.h"
#include "logs/log_input.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <matio.h>

#include "core/errors.h"
#include "logs/time_join.h"
#include "support/mat_fixture.h"

using namespace driveid;
using driveid::testing::Slurp;
using driveid::testing::WriteMat;

namespace {

const std::vector<std::string> kAxis = {"t", "q", "tau|i"};

CsvLog ReadOne(const std::string& path, const std::string& text, const LogInputOptions& options,
               const std::vector<JoinedFile>& joins = {}) {
  auto logs = ReadLogs(path, text, joins, kAxis, options);
  REQUIRE(logs.size() == 1);
  return std::move(logs.front());
}

template <typename Error = InputError>
std::string ErrorOf(const std::string& text, const LogInputOptions& options, const std::string& path = "log.csv") {
  try {
    ReadLogs(path, text, {}, kAxis, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

LogInputOptions Columns(std::map<std::string, std::string> columns) {
  LogInputOptions options;
  options.columns = std::move(columns);
  return options;
}

}  // namespace

TEST_CASE("CSV without header: columns by position, detected or forced") {
  const auto log = ReadOne("u.csv", "0,1.5,3\n0.01,1.6,4\n0.02,1.7,5\n",
                           Columns({{"t", "#1"}, {"q", "#2"}, {"tau", "10*#3"}}));
  CHECK(log.columns[1][2] == 1.7);
  CHECK(log.columns[2][0] == 30.0);
  CHECK(log.line_numbers == std::vector<int>{1, 2, 3});
  CHECK(log.notes.front() == "no header row: the first row holds numbers (columns are #1 .. #n)");
  CHECK(std::find(log.notes.begin(), log.notes.end(), "tau = 10*#3") != log.notes.end());
  // Forced: a first row that is text is data, and refused as a number.
  LogInputOptions forced = Columns({{"t", "#1"}, {"q", "#2"}, {"tau", "#3"}});
  forced.csv.no_header = true;
  CHECK(ErrorOf("t,q,tau\n0,1,2\n", forced) == "log.csv:1: column #1: not a number: \"t\"");
  CHECK_THAT(ErrorOf("0,1,2\n1,2,3\n", {}), Catch::StartsWith("log.csv: missing columns 't', 'q', 'tau' or 'i' (the file has no header: "
                                                                "name its 3 columns by position"));
  CHECK(ErrorOf("0,1,2\n1,2\n", forced) == "log.csv:2: 2 fields, but the first row has 3");
}

TEST_CASE("delimiters: semicolon, tab and blanks detected, or given") {
  for (const char* text : {"t;q;tau\n0;1;2\n1;2;3\n", "t\tq\ttau\n0\t1\t2\n1\t2\t3\n", "t  q tau\n0 1   2\n1 2 3\n"}) {
    const auto log = ReadOne("d.csv", text, {});
    CHECK(log.columns[0] == std::vector<double>{0, 1});
    CHECK(log.columns[2] == std::vector<double>{2, 3});
  }
  LogInputOptions semicolon;
  semicolon.csv.delimiter = ';';
  CHECK_THAT(ErrorOf("t,q,tau\n0,1,2\n", semicolon), Catch::Contains("missing columns 't', 'q'"));
}

TEST_CASE("column expressions: sums and differences of scaled columns (a coupled wrist)") {
  // Motor angles m5, m6 of a wrist where motor 5 turns joint 6 too:
  // q6 = m6/32 - m5/45, the CSV written by hand.
  const std::string text = "t,m5,m6,tau,dup-name\n0,90,64,1,7\n1,45,32,2,8\n";
  const auto log = ReadOne("w.csv", text, Columns({{"q", "#3/32 - #2/45"}, {"tau", "2*tau + 1e-3*m5 - -1*#5"}}));
  CHECK(log.columns[1][0] == Approx(64.0 / 32 - 90.0 / 45));
  CHECK(log.columns[1][1] == Approx(32.0 / 32 - 45.0 / 45));
  CHECK(log.columns[2][0] == Approx(2.0 + 0.09 + 7.0));
  CHECK(log.columns[2][1] == Approx(4.0 + 0.045 + 8.0));
  const auto leading = ReadOne("w.csv", text, Columns({{"q", "-m5 + m6"}, {"tau", "tau"}}));
  CHECK(leading.columns[1][0] == Approx(-26.0));
  // A header with a dash is named whole (inside a sum, by position).
  const auto whole = ReadOne("w.csv", text, Columns({{"q", "dup-name"}, {"tau", "tau"}}));
  CHECK(whole.columns[1][1] == 8.0);
  CHECK(ErrorOf<OptionError>(text, Columns({{"q", "m5 - m5/2"}, {"tau", "tau"}})) ==
        "‹col› q=m5 - m5/2: the column 'm5' appears twice; combine its factors");
  // Constants in a sum (issue 71): an encoder zero that is not the model's,
  // as an MDH offset, q2 = #2/32 - pi/2; before or after the columns.
  const auto offset = ReadOne("w.csv", text, Columns({{"q", "#3/32 - pi/2"}, {"tau", "0.5 + tau - 1e-1"}}));
  CHECK(offset.columns[1][0] == Approx(64.0 / 32 - M_PI / 2));
  CHECK(offset.columns[1][1] == Approx(32.0 / 32 - M_PI / 2));
  CHECK(offset.columns[2][1] == Approx(0.5 + 2.0 - 0.1));
  CHECK(ErrorOf<OptionError>(text, Columns({{"q", "3 - pi/2"}, {"tau", "tau"}})) ==
        "‹col› q=3 - pi/2: no column in the expression (a constant column is not a log)");
  CHECK(ErrorOf<OptionError>(text, Columns({{"q", "m5 -"}, {"tau", "tau"}})).find("an operand is missing") !=
        std::string::npos);
}

TEST_CASE("column expressions: factors, pi, division; refused forms are named") {
  const std::string text = "t,pos_deg,amps\n0,90,1\n1,180,2\n";
  const auto log = ReadOne("e.csv", text, Columns({{"q", "pi/180*pos_deg"}, {"i", "amps / 4"}}));
  CHECK(log.names[2] == "i");
  CHECK(log.columns[1][0] == Approx(M_PI / 2));
  CHECK(log.columns[2][1] == 0.5);
  CHECK(ErrorOf<OptionError>(text, Columns({{"q", "pos_deg*amps"}, {"tau", "amps"}})) ==
        "‹col› q=pos_deg*amps: two columns ('pos_deg' and 'amps') in one product; a term scales one column");
  CHECK(ErrorOf<OptionError>(text, Columns({{"q", "1/pos_deg"}, {"tau", "amps"}})) ==
        "‹col› q=1/pos_deg: the column 'pos_deg' may not be a divisor");
  CHECK(ErrorOf<OptionError>(text, Columns({{"q", "pos_deg/0"}, {"tau", "amps"}})) ==
        "‹col› q=pos_deg/0: division by zero ('0')");
  CHECK(ErrorOf<OptionError>(text, Columns({{"q", "2*degrees"}, {"tau", "amps"}})) ==
        "‹col› q=2*degrees: 'degrees' is neither a column of the log, a number, pi, nor a scalar of the file");
  CHECK(ErrorOf<OptionError>(text, Columns({{"q", "pos_deg*"}, {"tau", "amps"}})).find("an operand is missing") !=
        std::string::npos);
  CHECK(ErrorOf<OptionError>(text, Columns({{"q", "pos_deg"}, {"tau", "2*pos_deg"}})) ==
        "‹col›: 'q' and 'tau' would both read column 'pos_deg' of log.csv");
  CHECK_THAT(ErrorOf(text, Columns({{"q", "position"}})), Catch::StartsWith("log.csv:1: missing columns 'position', 'tau' or 'i'"));
}

TEST_CASE("--rate makes the time base; crops keep [from, to] in log time") {
  LogInputOptions rate = Columns({{"q", "#1"}, {"tau", "#2"}});
  rate.rate = 100.0;
  const auto log = ReadOne("r.csv", "1,2\n3,4\n5,6\n7,8\n", rate);
  CHECK(log.columns[0] == std::vector<double>{0.0, 0.01, 0.02, 0.03});
  LogInputOptions crop = rate;
  crop.from = 0.005;
  crop.to = 0.025;
  const auto cropped = ReadOne("r.csv", "1,2\n3,4\n5,6\n7,8\n", crop);
  CHECK(cropped.columns[1] == std::vector<double>{3, 5});
  CHECK(cropped.line_numbers == std::vector<int>{2, 3});
  crop.from = 5.0;
  crop.to = 6.0;
  CHECK(ErrorOf("1,2\n3,4\n", crop) == "log.csv: no samples between ‹from› 5 s and ‹to› 6 s (the log spans 0 .. 0.01 s)");
  LogInputOptions both;
  both.rate = 10.0;
  CHECK_THAT(ErrorOf<OptionError>("t,q,tau\n0,1,2\n", both), Catch::Contains("‹rate› is for logs without one"));
  CHECK(ErrorOf("t,q,tau\n0,1,2\n0,2,3\n", {}) == "log.csv:3: column 't': time not strictly increasing (0 after 0)");
}

TEST_CASE("--join: a second file's columns row by row, positions count on") {
  const std::string positions = "t,q\n0,1\n1,2\n2,3\n";
  const std::string currents = "0.5\n0.6\n0.7\n";
  const std::string short_file = "0.5\n0.6\n";
  const auto log = ReadOne("p.csv", positions, Columns({{"tau", "#3"}}), {{"c.csv", &currents, {}}});
  CHECK(log.columns[2] == std::vector<double>{0.5, 0.6, 0.7});
  CHECK(std::find(log.notes.begin(), log.notes.end(), "joined row by row with c.csv") != log.notes.end());
  CHECK_THROWS_WITH(ReadOne("p.csv", positions, Columns({{"tau", "#3"}}), {{"c.csv", &short_file, {}}}),
                    "p.csv: 3 rows, but c.csv (joined with ‹join›) has 2: a joined file must have one row per row "
                    "of the log");
}

TEST_CASE("--join-time: a second file on its own clock, interpolated onto the log's time") {
  // The log: t, q at 100 Hz over 2 s. The joined file: milliseconds on a clock 5 s ahead, at 40 Hz from
  // t = 0.5 s, a current c = 3 + 2 t (linear: interpolation is exact) and the speed the log's q is made of.
  const auto motion = [](double t) { return std::sin(3.0 * t) + 0.5 * std::tanh((t - 1.2) / 0.05); };
  std::string log = "t,q\n", joined = "stamp_ms,c,q2\n";
  for (int k = 0; k <= 200; ++k) log += fmt::format("{},{}\n", 0.01 * k, motion(0.01 * k));
  for (int k = 0; k <= 48; ++k) {
    const double t = 0.5 + 0.025 * k;
    joined += fmt::format("{},{},{}\n", 1000.0 * (t + 5.0), 3.0 + 2.0 * t, motion(t));
  }
  JoinTiming shift;
  shift.time = "stamp_ms/1000";
  shift.shift = -5.0;
  const auto a = ReadOne("p.csv", log, Columns({{"tau", "c"}}), {{"c.csv", &joined, shift}});
  REQUIRE(a.columns[0].size() == 121);  // 0.5 .. 1.7 s
  CHECK(a.columns[0].front() == Approx(0.5));
  CHECK(a.line_numbers.front() == 52);  // rows kept with their lines
  for (std::size_t i = 0; i < a.columns[0].size(); ++i) CHECK(a.columns[2][i] == Approx(3.0 + 2.0 * a.columns[0][i]));
  const auto has = [](const CsvLog& l, const std::string& text) {
    return std::any_of(l.notes.begin(), l.notes.end(), [&](const std::string& n) { return n.find(text) != n.npos; });
  };
  CHECK(has(a, "joined by time with c.csv"));
  CHECK(has(a, "121 of 201 samples kept (0.5 .. 1.7 s)"));
  CHECK(has(a, "c.csv is sampled at 40 Hz, the log at 100 Hz"));
  // The same shift found from the motion both files record.
  JoinTiming align;
  align.time = "stamp_ms/1000";
  align.align = "q=q2";
  const auto b = ReadOne("p.csv", log, Columns({{"tau", "c"}}), {{"c.csv", &joined, align}});
  INFO(fmt::format("{}", fmt::join(b.notes, " / ")));
  REQUIRE(b.columns[0].size() == 121);
  for (std::size_t i = 0; i < b.columns[0].size(); ++i) {
    CHECK(b.columns[2][i] == Approx(3.0 + 2.0 * b.columns[0][i]).margin(2e-3));
  }
  CHECK(has(b, "aligned by cross-correlation: shift -5"));
  // Refusals: no overlap; shift and align together; a shift without a time column; a time that goes back.
  shift.shift = 100.0;
  CHECK_THROWS_WITH(ReadOne("p.csv", log, Columns({{"tau", "c"}}), {{"c.csv", &joined, shift}}),
                    Catch::Contains("p.csv: the log spans 0 .. 2 s, c.csv spans 105.5 .. 106.7 s on its clock: they do "
                                    "not overlap"));
  shift.align = "q=q2";
  CHECK_THROWS_AS(ReadOne("p.csv", log, Columns({{"tau", "c"}}), {{"c.csv", &joined, shift}}), OptionError);
  JoinTiming untimed;
  untimed.shift = 1.0;
  CHECK_THROWS_WITH(ReadOne("p.csv", log, Columns({{"tau", "c"}}), {{"c.csv", &joined, untimed}}),
                    Catch::Contains("give the joined file's time column with ‹join-time›"));
  std::string backwards = joined;
  backwards.replace(backwards.find("\n5525,"), 6, "\n5000,");
  CHECK_THROWS_WITH(ReadOne("p.csv", log, Columns({{"tau", "c"}}), {{"c.csv", &backwards, align}}),
                    Catch::StartsWith("c.csv:3: the joined time ‹join-time› stamp_ms/1000 not strictly increasing"));
}

TEST_CASE("MAT v5 and v7.3: vectors, matrix columns and rows, struct fields, scalars in expressions") {
  for (mat_ft version : {MAT_FT_MAT5, MAT_FT_MAT73}) {
    const std::string bytes = WriteMat(version);
    INFO((version == MAT_FT_MAT73 ? "v7.3" : "v5"));
    // Without --col t=..., the variable `time` is the time base.
    const auto a = ReadOne("m.mat", bytes, Columns({{"q", "pi/180*data(:,2)"}, {"i", "gain*data(:,3)"}}));
    CHECK(a.columns[0][4] == 0.04);
    CHECK(a.columns[1][1] == Approx(20 * M_PI / 180));
    CHECK(a.columns[2] == std::vector<double>{2.5, 5, 7.5, 10, 12.5});
    CHECK(a.line_numbers.empty());
    const auto b = ReadOne("m.mat", bytes, Columns({{"t", "rec.time_cont"}, {"q", "rec.pos(1,:)"}, {"tau", "rec.pos(2,:)"}}));
    CHECK(b.columns[1] == std::vector<double>{1, 2, 3, 4, 5});
    CHECK(b.columns[2][4] == 500);
    // The complex variable is skipped with a note; asking for it says so.
    CHECK(std::find(b.notes.begin(), b.notes.end(), "z: skipped (complex numbers)") != b.notes.end());
    CHECK(ErrorOf(bytes, Columns({{"t", "time"}, {"q", "z"}, {"tau", "data(:,3)"}}), "m.mat") ==
          "m.mat: z: skipped (complex numbers)");
    // (v7.3 lists variables in HDF5's alphabetical order.)
    const std::string missing = ErrorOf(bytes, Columns({{"t", "time"}, {"q", "angle"}, {"tau", "data(:,3)"}}), "m.mat");
    CHECK_THAT(missing, Catch::StartsWith("m.mat: missing column 'angle' (the file has "));
    CHECK_THAT(missing, Catch::Contains("\"time\"") && Catch::Contains("\"data(:,1)\"") &&
                            Catch::Contains("\"rec.time_cont\""));
    CHECK(ErrorOf(bytes, Columns({{"t", "time"}, {"q", "rec.pos(1,:)"}, {"tau", "rec.time_cont"}}), "m.mat") ==
          "no error");
    CHECK(ErrorOf(bytes, Columns({{"t", "time"}, {"q", "rec.pos(1,:)"}, {"tau", "data(2,:)"}}), "m.mat") ==
          "m.mat: column 'data(2,:)' has 3 values but 'time' has 5: the columns of a log have one value per sample");
  }
  CHECK_THAT(ErrorOf(std::string("MATLAB 5.0 MAT-file") + std::string(200, '\0'), {}, "bad.mat"),
             Catch::StartsWith("bad.mat:"));
}

TEST_CASE("MAT: a wide matrix lists its rows, the other side on request; elements as scalars; variables listed") {
  for (mat_ft version : {MAT_FT_MAT5, MAT_FT_MAT73}) {
    const std::string bytes = WriteMat(version);
    INFO((version == MAT_FT_MAT73 ? "v7.3" : "v5"));
    const auto source = OpenMatSource("m.mat", bytes);
    const auto names = source->column_names();
    const auto listed = [&](const std::string& name) { return std::find(names.begin(), names.end(), name) != names.end(); };
    // rec.pos is 2 x 5 (wide): its rows are the signals; data is 5 x 3 (tall): its columns.
    CHECK(listed("rec.pos(1,:)"));
    CHECK(listed("rec.pos(2,:)"));
    CHECK_FALSE(listed("rec.pos(:,1)"));
    CHECK(listed("data(:,3)"));
    CHECK_FALSE(listed("data(1,:)"));
    REQUIRE(source->Find("rec.pos(:,4)"));
    CHECK(source->Read({*source->Find("rec.pos(:,4)")}).columns.front() == std::vector<double>{4, 400});
    CHECK_FALSE(source->Find("rec.pos(:,6)"));
    CHECK_FALSE(source->Find("rec.pos(3,:)"));
    // Elements of vectors and matrices are scalars: name(i) column-major, name(i,j).
    CHECK(source->scalar("gain") == 2.5);
    CHECK(source->scalar("gain(1)") == 2.5);
    CHECK(source->scalar("rec.pos(2,3)") == 300);
    CHECK(source->scalar("rec.pos(4)") == 200);
    CHECK(source->scalar("data(5,2)") == 50);
    CHECK_FALSE(source->scalar("rec.pos(3,1)"));
    CHECK_FALSE(source->scalar("rec.pos(11)"));
    CHECK_FALSE(source->scalar("rec.pos(0)"));
    CHECK_FALSE(source->scalar("rec.pos(1,)"));
    const auto b = ReadOne("m.mat", bytes, Columns({{"t", "time"}, {"q", "rec.pos(2,1)*rec.pos(1,:)"}, {"tau", "data(:,3)"}}));
    CHECK(b.columns[1] == std::vector<double>{100, 200, 300, 400, 500});
    // Variables and struct fields with their sizes and how to address them.
    const auto variables = source->variables();
    const auto pos = std::find_if(variables.begin(), variables.end(), [](const SourceVariable& v) { return v.name == "rec.pos"; });
    REQUIRE(pos != variables.end());
    CHECK(pos->rows == 2);
    CHECK(pos->cols == 5);
    CHECK(pos->address == "rows rec.pos(1,:) .. rec.pos(2,:); columns rec.pos(:,k)");
  }
}

TEST_CASE("SysId JSON: four tests as logs, positions in units, sides of a drivetrain") {
  const std::string simple = R"({"test": "Simple", "units": "Radians", "unitsPerRotation": 6.0, "sysid": true,
    "slow-forward": [[0, 1, 0.5, 0.1], [0.005, 1.1, 0.6, 0.2]], "slow-backward": [[1, -1, 2, -0.1], [1.005, -1.1, 1.9, -0.2]],
    "fast-forward": [[2, 7, 0, 0], [2.005, 7, 0.1, 1]], "fast-backward": [[3, -7, 0, 0], [3.005, -7, -0.1, -1]]})";
  const auto logs = ReadLogs("s.json", simple, {}, kAxis, {});
  REQUIRE(logs.size() == 4);
  CHECK(logs[0].segment == "slow-forward");
  CHECK(logs[0].columns[1][0] == 3.0);
  CHECK(logs[0].columns[1][1] == Approx(3.6));
  CHECK(logs[1].columns[2] == std::vector<double>{-1, -1.1});
  CHECK(logs[3].segment == "fast-backward");
  const std::string drive = R"({"test": "Drivetrain", "units": "Meters", "unitsPerRotation": 0.5,
    "slow-forward": [[0, 1, 2, 10, 20, 0, 0, 0, 0], [1, 1, 2, 11, 21, 1, 1, 0, 0]],
    "slow-backward": [[0, 1, 2, 10, 20, 0, 0, 0, 0], [1, 1, 2, 11, 21, 1, 1, 0, 0]],
    "fast-forward": [[0, 1, 2, 10, 20, 0, 0, 0, 0], [1, 1, 2, 11, 21, 1, 1, 0, 0]],
    "fast-backward": [[0, 1, 2, 10, 20, 0, 0, 0, 0], [1, 1, 2, 11, 21, 1, 1, 0, 0]]})";
  LogInputOptions both;
  both.selection.sysid.side = "both";
  const auto sides = ReadLogs("d.json", drive, {}, kAxis, both);
  REQUIRE(sides.size() == 8);
  CHECK(sides[1].segment == "slow-forward/right");
  CHECK(sides[1].columns[1] == std::vector<double>{10, 10.5});
  CHECK(sides[1].columns[2] == std::vector<double>{2, 2});
  CHECK_THAT(ErrorOf<OptionError>(drive, {}, "d.json"), Catch::Contains("give ‹side› left, right or both"));
  CHECK(ErrorOf(R"({"test": "Simple", "unitsPerRotation": 1, "slow-forward": [[0, 1]]})", {}, "x.json") ==
        "x.json: slow-forward[0]: expected 4 numbers per sample for the Simple layout, found 2");
  CHECK(ErrorOf("{\"test\": ", {}, "x.json").rfind("x.json: invalid JSON at byte", 0) == 0);
  // Fuzzer regression: a number beyond double's range is an input error, not a crash.
  CHECK(ErrorOf(R"({"test": "Simple", "unitsPerRotation": 1e999})", {}, "x.json").rfind("x.json: invalid JSON", 0) == 0);
}

TEST_CASE("fuzzer regression: a MAT variable whose compressed data claims 2 GB is refused in well under a second") {
  // tests/fuzz/regressions/log_input_mat_inflated_tag.bin: a 4 x 3 double whose
  // inner tag makes matio allocate 2 GB; the reader's child process has an
  // address-space cap scaled to the file, so the allocation fails at once.
  const char* source_dir = std::getenv("DRIVEID_SOURCE_DIR");
  REQUIRE(source_dir != nullptr);
  std::ifstream in(std::string(source_dir) + "/tests/fuzz/regressions/log_input_mat_inflated_tag.bin",
                   std::ios::binary);
  REQUIRE(in);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  const std::string text = bytes.str().substr(1);  // the first byte picks the fuzzer's reader
  const auto start = std::chrono::steady_clock::now();
  try {
    OpenMatSource("hostile.mat", text);
  } catch (const InputError&) {
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  bool sanitized = false;  // no address-space cap under AddressSanitizer
#if defined(__SANITIZE_ADDRESS__)
  sanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  sanitized = true;
#endif
#endif
  CHECK(seconds < (sanitized ? 30.0 : 0.5));
}

TEST_CASE("fuzzer regression: a MAT v7.3 file on which HDF5 spins is refused after the reader's 5 s") {
  // tests/fuzz/regressions/log_input_mat73_spin.bin: HDF5 loops on it; the
  // reader's child is killed after 5 s + 1 s per 10 MB.
  const char* source_dir = std::getenv("DRIVEID_SOURCE_DIR");
  REQUIRE(source_dir != nullptr);
  std::ifstream in(std::string(source_dir) + "/tests/fuzz/regressions/log_input_mat73_spin.bin", std::ios::binary);
  REQUIRE(in);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  const auto start = std::chrono::steady_clock::now();
  std::string message;
  try {
    OpenMatSource("spin.mat", bytes.str().substr(1));
  } catch (const InputError& e) {
    message = e.what();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK(message == "spin.mat: the MAT reader took longer than 5 s (a corrupt file?)");
  CHECK(seconds < 7.0);
}

TEST_CASE("derived signals: integral, derivative and detrend of a column, over the (cropped) time base") {
  // t irregular; speed w = 2 t, so integral = t^2 - t0^2 and derivative = 2.
  std::string text = "t,w,tau\n";
  const double times[] = {0.0, 0.1, 0.25, 0.3, 0.5, 0.8, 1.0};
  for (double t : times) text += fmt::format("{},{},{}\n", t, 2.0 * t, 1.0 + t);
  LogInputOptions options;
  options.columns = {{"q", "integral(w)"}};
  const CsvLog integral = ReadOne("d.csv", text, options);
  for (std::size_t i = 0; i < 7; ++i) CHECK(std::abs(integral.columns[1][i] - times[i] * times[i]) < 1e-12);
  options.columns = {{"q", "derivative(0.5*w)"}};
  const CsvLog derivative = ReadOne("d.csv", text, options);
  for (double v : derivative.columns[1]) CHECK(std::abs(v - 1.0) < 1e-12);
  options.columns = {{"q", "detrend(w)"}, {"tau", "integral(detrend(w))"}};
  const CsvLog both = ReadOne("d.csv", text, options);
  double mean = 0.0;
  for (double v : both.columns[1]) mean += v;
  CHECK(std::abs(mean) < 1e-12);
  CHECK(both.columns[2][0] == 0.0);
  // Crops first: the integral is 0 at the first kept sample.
  options.columns = {{"q", "integral(w)"}};
  options.from = 0.25;
  const CsvLog cropped = ReadOne("d.csv", text, options);
  CHECK(cropped.columns[1][0] == 0.0);
  CHECK(std::abs(cropped.columns[1].back() - (1.0 - 0.0625)) < 1e-12);
  options.from.reset();
  // The same source column twice: allowed when derived signals differ.
  options.columns = {{"q", "integral(w)"}, {"tau", "w"}};
  const CsvLog twice = ReadOne("d.csv", text, options);
  CHECK(twice.columns[2][6] == 2.0);
  CHECK(std::abs(twice.columns[1][6] - 1.0) < 1e-12);
  options.columns = {{"q", "w"}, {"tau", "w"}};
  CHECK(ErrorOf<OptionError>(text, options).find("would both read column 'w'") != std::string::npos);
  options.columns = {{"q", "integral()"}};
  CHECK(ErrorOf<OptionError>(text, options).find("integral() of nothing") != std::string::npos);
  options.columns = {{"t", "integral(t)"}, {"q", "w"}};
  CHECK(ErrorOf<OptionError>(text, options).find("the time base cannot be derived") != std::string::npos);
}

TEST_CASE("MAT v5 cut short at every length: refused naming the file, or the same data as the whole file") {
  // Issue 21: matio read a cut-short v5 element as zeros (exit 0). Every
  // prefix of a small file (compressed `data`, uncompressed `time`, a struct,
  // a complex variable) either throws InputError naming the file or reads
  // exactly what the whole file reads.
  // (v7.3, 13 kB of HDF5, in tests/logs/mat_hostile_test.cc)
  for (mat_ft version : {MAT_FT_MAT5}) {
    const std::string bytes = WriteMat(version);
    INFO("v5, " << bytes.size() << " bytes");
    const LogInputOptions options = Columns({{"q", "data(:,2)"}, {"i", "data(:,3)"}});
    const CsvLog whole = ReadOne("whole.mat", bytes, options);
    int refused = 0, same = 0;
    for (std::size_t length = 0; length < bytes.size(); ++length) {
      try {
        const auto logs = ReadLogs("cut.mat", bytes.substr(0, length), {}, kAxis, options);
        INFO("prefix of " << length << " bytes read");
        REQUIRE(logs.size() == 1);
        CHECK(logs[0].columns == whole.columns);
        ++same;
      } catch (const InputError& e) {
        INFO("prefix of " << length << " bytes: " << e.what());
        CHECK(std::string(e.what()).rfind("cut.mat", 0) == 0);
        ++refused;
      }
    }
    CHECK(refused > 0);
    INFO("refused " << refused << ", same " << same);
  }
}

TEST_CASE("MAT v5: a cut-short element and a compressed element shorter than its header are refused by name") {
  const std::string bytes = WriteMat(MAT_FT_MAT5);
  const LogInputOptions options = Columns({{"q", "data(:,2)"}, {"i", "data(:,3)"}});
  // The last variable (z, uncompressed) loses its last 8 bytes.
  CHECK_THAT(ErrorOf(bytes.substr(0, bytes.size() - 8), options, "cut.mat"),
             Catch::Matches("cut.mat: variable z is cut short: the file ends 8 bytes before its end .*"));
  // `data` is compressed: change its inner tag's byte count by re-deflating is
  // beyond this test; cutting inside it names it from its inflated header.
  const std::size_t data_at = bytes.find(std::string("\x0f\x00\x00\x00", 4), 128);
  REQUIRE(data_at != std::string::npos);
  CHECK_THAT(ErrorOf(bytes.substr(0, data_at + 8 + 20), options, "cut.mat"),
             Catch::Matches("cut.mat: data element 2 \\(its name unreadable\\) is cut short.*|cut.mat: variable data is cut short.*"));
}
