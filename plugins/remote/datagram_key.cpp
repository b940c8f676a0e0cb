#include "datagram_key.hpp"

#include <sodium.h>

#include <fstream>
#include <iterator>

namespace s2sim::links {

void DatagramKey::load(const std::string& path, const Location& where) {
  if (sodium_init() < 0)
    throw Error(ErrorKind::runtime, where, "libsodium could not be initialised");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(ErrorKind::scene, where, "cannot read the key file '" + path + "'");
  key_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (!key_.empty() && key_.back() == '\n') key_.pop_back();
  if (key_.size() < kMinKeyBytes) {
    const std::size_t got = key_.size();
    key_.clear();
    throw Error(ErrorKind::scene, where,
                "the key file '" + path + "' holds " + std::to_string(got) +
                    " bytes; a key needs at least " + std::to_string(kMinKeyBytes));
  }
}

void DatagramKey::seal(unsigned char* data, std::size_t size) const {
  crypto_auth_hmacsha256_state state;
  crypto_auth_hmacsha256_init(&state, key_.data(), key_.size());
  crypto_auth_hmacsha256_update(&state, data, size);
  crypto_auth_hmacsha256_final(&state, data + size);
}

bool DatagramKey::verify(const unsigned char* data, std::size_t size) const {
  if (size < kTagSize) return false;
  unsigned char tag[kTagSize];
  crypto_auth_hmacsha256_state state;
  crypto_auth_hmacsha256_init(&state, key_.data(), key_.size());
  crypto_auth_hmacsha256_update(&state, data, size - kTagSize);
  crypto_auth_hmacsha256_final(&state, tag);
  return sodium_memcmp(tag, data + size - kTagSize, kTagSize) == 0;
}

}  // namespace s2sim::links
