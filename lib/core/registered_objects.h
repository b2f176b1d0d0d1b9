// The objects a registry makes once from its factories, in the order its
// list (a DRIVEID_..._TERMS or _FORMATS list of lib/CMakeLists.txt) gives
// them: the axis's, the elastic joint's and the serial drive's terms.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace driveid {

template <class T>
struct RegisteredObjects {
  std::vector<std::unique_ptr<T>> owned;
  std::vector<const T*> list;  ///< the owned objects, in the factories' order
};

template <class T, std::size_t N>
RegisteredObjects<T> MakeRegisteredObjects(std::unique_ptr<T> (*const (&factories)[N])()) {
  RegisteredObjects<T> out;
  for (const auto make : factories) {
    out.owned.push_back(make());
    out.list.push_back(out.owned.back().get());
  }
  return out;
}

}  // namespace driveid
