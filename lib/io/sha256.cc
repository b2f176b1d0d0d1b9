#include "io/sha256.h"

#include <stdexcept>

#include <openssl/evp.h>

namespace driveid {

// OpenSSL's libcrypto (Debian libssl-dev): its assembler SHA-256 hashes at
// memory speed, several times the hand-written loop it replaced.
std::string Sha256Hex(const std::string& bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), digest, &length, EVP_sha256(), nullptr) != 1 || length != 32) {
    throw std::runtime_error("SHA-256: OpenSSL's EVP_Digest failed");
  }
  static const char kHex[] = "0123456789abcdef";
  std::string out(2 * length, '0');
  for (unsigned int i = 0; i < length; ++i) {
    out[2 * i] = kHex[digest[i] >> 4];
    out[2 * i + 1] = kHex[digest[i] & 15];
  }
  return out;
}

}  // namespace driveid
