// The tools' JSON text (report/json.h): keys in the order written,
// non-finite numbers as null, bytes that are not UTF-8 replaced (a file
// name from the command line) rather than aborting, one line per document.
#include <cmath>
#include <limits>

#include <catch2/catch.hpp>

#include "report/json.h"

namespace driveid {
namespace {

TEST_CASE("DumpJson: written order, null for non-finite numbers, U+FFFD for bytes that are not UTF-8") {
  Json document;
  document["zeta"] = 1.5;
  document["alpha"] = std::nan("");
  document["mid"] = Json::array({std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), 2});
  document["file"] = std::string("log\xff\xfe.csv");
  const std::string text = DumpJson(document);
  CHECK(text == "{\"zeta\":1.5,\"alpha\":null,\"mid\":[null,null,2],\"file\":\"log\xef\xbf\xbd\xef\xbf\xbd.csv\"}\n");
  // It reads back as a document (the replaced name included).
  const Json back = Json::parse(text);
  CHECK(back["zeta"] == 1.5);
  CHECK(back["alpha"].is_null());
  CHECK(back["file"].get<std::string>() == "log\xef\xbf\xbd\xef\xbf\xbd.csv");
}

}  // namespace
}  // namespace driveid
