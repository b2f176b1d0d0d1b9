#include "logs/formats/hdf5_storage_check.h"

#include <fmt/format.h>
#include <hdf5.h>

#include "core/errors.h"

namespace driveid {
namespace {

struct Visit {
  std::string refused;  // "" while every object so far is the file's own
};

herr_t CheckLink(hid_t group, const char* name, const H5L_info_t* info, void* data) {
  auto& visit = *static_cast<Visit*>(data);
  if (info->type == H5L_TYPE_EXTERNAL) {
    visit.refused = fmt::format("'{}' is an external link (to an object in another file)", name);
    return 1;
  }
  if (info->type != H5L_TYPE_HARD) return 0;  // soft links name objects visited through their hard links
  H5O_info_t object{};
  if (H5Oget_info_by_name(group, name, &object, H5P_DEFAULT) < 0 || object.type != H5O_TYPE_DATASET) return 0;
  const hid_t dataset = H5Dopen2(group, name, H5P_DEFAULT);
  if (dataset < 0) return 0;
  const hid_t plist = H5Dget_create_plist(dataset);
  if (plist >= 0) {
    if (H5Pget_external_count(plist) > 0) {
      visit.refused = fmt::format("variable '{}' keeps its data in external files", name);
    } else if (H5Pget_layout(plist) == H5D_VIRTUAL) {
      visit.refused = fmt::format("variable '{}' is a virtual dataset (mapped from other files)", name);
    }
    H5Pclose(plist);
  }
  H5Dclose(dataset);
  return visit.refused.empty() ? 0 : 1;
}

}  // namespace

void CheckHdf5Storage(const std::string& path, const std::string& file) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // no error stack on stderr
  if (H5Fis_hdf5(file.c_str()) <= 0) return;
  const hid_t handle = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (handle < 0) return;
  Visit visit;
  H5Lvisit(handle, H5_INDEX_NAME, H5_ITER_NATIVE, CheckLink, &visit);
  H5Fclose(handle);
  if (!visit.refused.empty()) {
    throw InputError(fmt::format("{}: {}: a log may only supply its own bytes; refused", path, visit.refused));
  }
}

}  // namespace driveid
