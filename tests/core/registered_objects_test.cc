// core/registered_objects.h: a registry's objects are made once each, in
// the factories' order, and handed out as the owned objects themselves;
// core/name_list.h: Contains finds a name exactly (no prefix, no case folding).
#include <memory>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/name_list.h"
#include "core/registered_objects.h"

using namespace driveid;

namespace {

struct Named {
  virtual ~Named() = default;
  virtual std::string name() const = 0;
};
int made = 0;
struct First final : Named {
  std::string name() const override { return "first"; }
};
struct Second final : Named {
  std::string name() const override { return "second"; }
};
std::unique_ptr<Named> MakeFirst() {
  ++made;
  return std::make_unique<First>();
}
std::unique_ptr<Named> MakeSecond() {
  ++made;
  return std::make_unique<Second>();
}
using Make = std::unique_ptr<Named> (*)();
const Make kFactories[] = {MakeSecond, MakeFirst};

}  // namespace

TEST_CASE("registered objects: one each, in the factories' order, owned") {
  made = 0;
  const RegisteredObjects<Named> r = MakeRegisteredObjects(kFactories);
  CHECK(made == 2);
  REQUIRE(r.list.size() == 2);
  CHECK(r.list[0]->name() == "second");
  CHECK(r.list[1]->name() == "first");
  CHECK(r.list[0] == r.owned[0].get());
  CHECK(r.list[1] == r.owned[1].get());
}

TEST_CASE("name list: Contains is an exact match") {
  const std::vector<std::string> names = {"viscous", "coulomb_pos"};
  CHECK(Contains(names, "viscous"));
  CHECK(Contains(names, "coulomb_pos"));
  CHECK_FALSE(Contains(names, "coulomb"));
  CHECK_FALSE(Contains(names, "Viscous"));
  CHECK_FALSE(Contains({}, "viscous"));
}
