// What `validate MODEL.xml` lets MuJoCo read (sim/mjcf_files.h): files in
// the model's folder only. Each way out is refused naming the file and the
// reference: absolute paths, "..", entities, links leading out, what is not
// a regular file, a cube texture's face files, and includes nested too deep.
#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>

#include <stdlib.h>

#include "core/errors.h"
#include "sim/mjcf_files.h"

namespace driveid {
namespace {

namespace fs = std::filesystem;

struct Folder {
  Folder() {
    char pattern[] = "/tmp/driveid-mjcf-test-XXXXXX";
    REQUIRE(::mkdtemp(pattern) != nullptr);
    path = pattern;
  }
  ~Folder() { fs::remove_all(path); }
  std::string Write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name) << text;
    return (path / name).string();
  }
  fs::path path;
};

std::string Model(const std::string& asset) {
  return "<mujoco>\n<asset>\n" + asset + "\n</asset>\n<worldbody/>\n</mujoco>\n";
}

TEST_CASE("files in the model's folder are accepted, with a mesh folder and an include") {
  Folder folder;
  fs::create_directory(folder.path / "meshes");
  folder.Write("meshes/arm.stl", "solid");
  folder.Write("part.xml", "<mujocoinclude><body/></mujocoinclude>");
  const std::string model = folder.Write(
      "model.xml", "<mujoco>\n<compiler meshdir='meshes'/>\n<include file=\"part.xml\"/>\n<asset><mesh file=\"meshes/arm.stl\"/>"
                   "<texture type=\"skybox\" fileright = 'sky.png'/></asset>\n</mujoco>\n");
  CHECK_NOTHROW(CheckMjcfFiles(model));
}

TEST_CASE("every way out of the folder is refused, naming the file, the attribute and why") {
  Folder folder;
  fs::create_directory(folder.path / "sub");
  fs::create_symlink("/etc", folder.path / "out");
  const struct {
    std::string asset, why;
  } cases[] = {
      {"<mesh file=\"/etc/passwd\"/>", "file=\"/etc/passwd\": an absolute path"},
      {"<mesh file=\"sub/../../x.stl\"/>", "a '..'"},
      {"<mesh file=\"&#47;etc/passwd\"/>", "a character reference or entity"},
      {"<mesh file=\"out/passwd\"/>", "a link that leads outside the model's folder"},
      {"<mesh file=\"sub\"/>", "not a regular file"},
      {"<hfield file='/dev/zero'/>", "an absolute path"},
      {"<texture type=\"skybox\" fileright=\"/dev/zero\"/>", "fileright=\"/dev/zero\": an absolute path"},
      {"<texture type=\"cube\" fileup=\"../x.png\"/>", "fileup=\"../x.png\": a '..'"},
      {"<texture type=\"cube\"\n fileback=\"/x.png\"/>", "fileback"},
      {"<texture type=\"cube\" filefront=\"sub\"/>", "filefront=\"sub\": not a regular file"},
      {"</asset><compiler meshdir=\"/usr\"/><asset>", "meshdir=\"/usr\": an absolute path"},
  };
  for (const auto& c : cases) {
    const std::string model = folder.Write("model.xml", Model(c.asset));
    INFO(c.asset);
    CHECK_THROWS_WITH(CheckMjcfFiles(model), Catch::Contains(model + ": ") && Catch::Contains(c.why) &&
                                                 Catch::Contains("MuJoCo may read only files in the model's folder"));
  }
}

TEST_CASE("an included file is checked too; includes nested past 8 are refused") {
  Folder folder;
  folder.Write("bad.xml", "<mujocoinclude><asset><mesh file=\"/etc/shadow\"/></asset></mujocoinclude>");
  const std::string model = folder.Write("model.xml", "<mujoco><include file=\"bad.xml\"/></mujoco>");
  CHECK_THROWS_WITH(CheckMjcfFiles(model), Catch::Contains("bad.xml: file=\"/etc/shadow\": an absolute path"));
  // A file including itself: nested ever deeper.
  const std::string loop = folder.Write("loop.xml", "<mujoco><include file=\"loop.xml\"/></mujoco>");
  CHECK_THROWS_WITH(CheckMjcfFiles(loop), Catch::Contains("includes nested more than 8 deep"));
}

}  // namespace
}  // namespace driveid
