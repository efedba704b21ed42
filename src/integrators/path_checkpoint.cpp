#include "integrators/path_checkpoint.h"

#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "util/atomic_file.h"
#include "util/error.h"
#include "util/hash.h"

namespace candela {

namespace {

constexpr char kMagic[] = "CANDELA-PATH-CHECKPOINT 1\n";
constexpr std::size_t kMagicSize = sizeof(kMagic) - 1;

template <typename T>
void put(std::string& out, const T& value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

class Reader {
 public:
  Reader(const std::string& bytes, const std::string& path) : bytes_(bytes), path_(path) {}
  template <typename T>
  T get() {
    T value;
    need(sizeof(T));
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  std::string get_string(std::size_t size) {
    need(size);
    std::string value = bytes_.substr(at_, size);
    at_ += size;
    return value;
  }
  std::size_t position() const { return at_; }
  [[noreturn]] void fail(const std::string& message) const { throw InputError({path_, 0, 0, {}}, message); }

 private:
  void need(std::size_t size) const {
    if (bytes_.size() - at_ < size) fail("the checkpoint is truncated");
  }
  const std::string& bytes_;
  const std::string& path_;
  std::size_t at_ = 0;
};

}  // namespace

void write_path_checkpoint(const std::string& path, const PathCheckpoint& checkpoint) {
  std::string bytes(kMagic, kMagicSize);
  put(bytes, static_cast<uint64_t>(checkpoint.fingerprint.size()));
  bytes += checkpoint.fingerprint;
  for (const int v : {checkpoint.region.x0, checkpoint.region.y0, checkpoint.region.x1, checkpoint.region.y1})
    put(bytes, static_cast<int32_t>(v));
  put(bytes, checkpoint.passes);
  put(bytes, checkpoint.seconds);
  for (const uint64_t count : {checkpoint.rays.primary, checkpoint.rays.shadow, checkpoint.rays.reflected,
                               checkpoint.rays.refracted})
    put(bytes, count);
  put(bytes, static_cast<uint64_t>(checkpoint.sums.size()));
  for (const Color& sum : checkpoint.sums) {
    put(bytes, sum.r);
    put(bytes, sum.g);
    put(bytes, sum.b);
  }
  put(bytes, fnv1a_64(bytes));
  write_atomically(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) throw std::runtime_error("cannot write the checkpoint " + path);
  });
}

PathCheckpoint read_path_checkpoint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, 0, 0, {}}, "cannot open the checkpoint");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Reader reader(bytes, path);
  if (bytes.compare(0, kMagicSize, kMagic) != 0) reader.fail("not a candela path-tracing checkpoint");
  reader.get_string(kMagicSize);
  PathCheckpoint checkpoint;
  const auto fingerprint_size = reader.get<uint64_t>();
  if (fingerprint_size > bytes.size()) reader.fail("the checkpoint is corrupt (fingerprint size)");
  checkpoint.fingerprint = reader.get_string(fingerprint_size);
  checkpoint.region.x0 = reader.get<int32_t>();
  checkpoint.region.y0 = reader.get<int32_t>();
  checkpoint.region.x1 = reader.get<int32_t>();
  checkpoint.region.y1 = reader.get<int32_t>();
  checkpoint.passes = reader.get<uint64_t>();
  checkpoint.seconds = reader.get<double>();
  checkpoint.rays.primary = reader.get<uint64_t>();
  checkpoint.rays.shadow = reader.get<uint64_t>();
  checkpoint.rays.reflected = reader.get<uint64_t>();
  checkpoint.rays.refracted = reader.get<uint64_t>();
  const auto pixel_count = reader.get<uint64_t>();
  const PixelRect& r = checkpoint.region;
  if (r.width() <= 0 || r.height() <= 0 || pixel_count != uint64_t(r.width()) * uint64_t(r.height()) ||
      pixel_count > bytes.size() / (3 * sizeof(double)))
    reader.fail("the checkpoint is corrupt (image size)");
  checkpoint.sums.resize(pixel_count);
  for (Color& sum : checkpoint.sums) {
    sum.r = reader.get<double>();
    sum.g = reader.get<double>();
    sum.b = reader.get<double>();
  }
  const std::size_t body = reader.position();
  const auto checksum = reader.get<uint64_t>();
  if (checksum != fnv1a_64(bytes.substr(0, body))) reader.fail("the checkpoint is corrupt (checksum mismatch)");
  if (reader.position() != bytes.size()) reader.fail("the checkpoint has trailing bytes");
  return checkpoint;
}

}  // namespace candela
