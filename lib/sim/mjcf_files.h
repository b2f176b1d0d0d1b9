// The files an MJCF makes MuJoCo read (docs/export.md#validation-in-mujoco):
// `<include file>`, asset `file` attributes (meshes, textures and a cube
// texture's six face files `fileright` .. `fileback`, height
// fields, skins) and the compiler's `meshdir`, `texturedir`, `assetdir`.
// `validate MODEL.xml` lets MuJoCo read only what lies in the model's
// folder: each reference is checked before MuJoCo opens anything, and
// included files are checked the same way (at most 8 deep, 64 files).
#pragma once

#include <string>

namespace driveid {

/// Throws InputError naming the file (the model or an included one) and the
/// reference: an absolute path, a "..", a character reference or entity
/// (`&`, which tinyxml2 decodes into any path), a path that leads outside
/// the model's folder through a link, or one that is not a regular file.
void CheckMjcfFiles(const std::string& model_path);

}  // namespace driveid
