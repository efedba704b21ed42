// The one byte format of messages between ranks and of checkpoints (io/byte_stream.h), and the
// checkpoint file around it (io/checkpoint_file.h): round trips bit for bit, and every short or
// damaged input refused with the error its reader promises.
#include "io/byte_stream.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "io/checkpoint_file.h"
#include "scratch_directory.h"
#include "util/error.h"

namespace candela {
namespace {

TEST(ByteStream, ValuesArraysAndStringsRoundTripExactly) {
  ByteWriter writer;
  writer.put<uint64_t>(42);
  writer.put(-0.0);
  writer.put(std::numeric_limits<double>::denorm_min());
  writer.put_array(std::vector<int32_t>{-1, 2, 3});
  writer.put_array(std::vector<double>{});
  writer.put_string("two\0words");
  writer.put_string("");
  const Bytes bytes = writer.take();
  ByteReader reader(bytes);
  EXPECT_EQ(reader.get<uint64_t>(), 42u);
  const double zero = reader.get<double>();
  EXPECT_EQ(zero, 0.0);
  EXPECT_TRUE(std::signbit(zero));
  EXPECT_EQ(reader.get<double>(), std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(reader.get_array<int32_t>(), (std::vector<int32_t>{-1, 2, 3}));
  EXPECT_TRUE(reader.get_array<double>().empty());
  EXPECT_EQ(reader.get_string(), "two");
  EXPECT_EQ(reader.get_string(), "");
  EXPECT_EQ(reader.remaining(), 0u);
}

TEST(ByteStream, ReadingPastTheEndThrowsNamingTheStream) {
  ByteWriter writer;
  writer.put<uint32_t>(7);
  const Bytes bytes = writer.take();
  ByteReader reader(bytes);
  try {
    (void)reader.get<uint64_t>();
    ADD_FAILURE() << "read past the end";
  } catch (const ByteStreamError& e) {
    EXPECT_EQ(e.kind(), ByteStreamError::Kind::short_value);
    EXPECT_STREQ(e.what(), "distributed message: shorter than expected");
  }
  // A count larger than the bytes left: refused before allocating.
  ByteWriter long_array;
  long_array.put<uint64_t>(uint64_t(1) << 60);
  const Bytes array_bytes = long_array.take();
  ByteReader array_reader(array_bytes, "test stream");
  try {
    (void)array_reader.get_array<double>();
    ADD_FAILURE() << "an array past the end";
  } catch (const ByteStreamError& e) {
    EXPECT_EQ(e.kind(), ByteStreamError::Kind::long_array);
    EXPECT_STREQ(e.what(), "test stream: array past its end");
  }
  ByteWriter long_string;
  long_string.put<uint64_t>(5);
  const Bytes string_bytes = long_string.take();
  ByteReader string_reader(string_bytes);
  EXPECT_THROW((void)string_reader.get_string(), ByteStreamError);
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// The message of the InputError reading `path` as a test checkpoint gives, with the file named.
std::string checkpoint_error(const std::string& path) {
  try {
    CheckpointReader in(read_checkpoint_file(path), "TEST-CHECKPOINT 1\n");
    (void)in.get_string();
    (void)in.get_colors();
    (void)in.get<double>();
    in.finish();
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().file, path);
    return e.message();
  }
  ADD_FAILURE() << "no error for " << path;
  return "";
}

TEST(CheckpointFile, RoundTripsAndRefusesEveryDamage) {
  const testing::ScratchDirectory directory("checkpoint-file");
  const std::string path = (directory.path() / "t.checkpoint").string();
  CheckpointWriter out("TEST-CHECKPOINT 1\n");
  out.put_string("fingerprint");
  out.put_colors({Color(0.1, 1e-300, 3), Color(-0.0, 2, 5e300)});
  out.put(1.0 / 3);
  write_checkpoint_file(path, out.seal());
  const std::string bytes = read_bytes(path);
  EXPECT_EQ(bytes.rfind("TEST-CHECKPOINT 1\n", 0), 0u);
  {
    CheckpointReader in(read_checkpoint_file(path), "TEST-CHECKPOINT 1\n");
    EXPECT_EQ(in.get_string(), "fingerprint");
    const std::vector<Color> colors = in.get_colors();
    ASSERT_EQ(colors.size(), 2u);
    EXPECT_EQ(colors[0], Color(0.1, 1e-300, 3));
    EXPECT_EQ(colors[1], Color(-0.0, 2, 5e300));
    EXPECT_EQ(in.get<double>(), 1.0 / 3);
    in.finish();
  }
  EXPECT_NE(checkpoint_error(path + ".absent").find("cannot open the checkpoint"), std::string::npos);
  write_bytes(path, "OTHER-CHECKPOINT 1\n" + bytes.substr(18));
  EXPECT_EQ(checkpoint_error(path), "not a TEST-CHECKPOINT 1 checkpoint");
  write_bytes(path, bytes.substr(0, bytes.size() - 3));
  EXPECT_NE(checkpoint_error(path).find("checksum mismatch"), std::string::npos);
  write_bytes(path, "TEST-CHECKPOINT 1\n");
  EXPECT_EQ(checkpoint_error(path), "the checkpoint is truncated");

  // Well-formed files (right checksum) whose fields do not add up.
  const auto write_fields = [&](ByteWriter& fields) {
    CheckpointWriter file("TEST-CHECKPOINT 1\n");
    const Bytes& raw = fields.bytes();
    for (const std::byte b : raw) file.put(b);
    write_checkpoint_file(path, file.seal());
  };
  ByteWriter short_fields;
  short_fields.put_string("fingerprint");
  write_fields(short_fields);
  EXPECT_EQ(checkpoint_error(path), "the checkpoint is truncated");
  ByteWriter huge_count;
  huge_count.put_string("fingerprint");
  huge_count.put<uint64_t>(uint64_t(1) << 60);
  write_fields(huge_count);
  EXPECT_EQ(checkpoint_error(path), "the checkpoint is corrupt (color count)");
  ByteWriter extra;
  extra.put_string("fingerprint");
  extra.put_array(std::vector<Color>{});
  extra.put(0.5);
  extra.put<uint8_t>(1);
  write_fields(extra);
  EXPECT_EQ(checkpoint_error(path), "the checkpoint has bytes this version does not know");

  // A valid checksum over sums that are NaN or infinite resumed into a NaN image.
  for (const double bad : {std::nan(""), HUGE_VAL, -HUGE_VAL}) {
    CheckpointWriter not_finite("TEST-CHECKPOINT 1\n");
    not_finite.put_string("fingerprint");
    not_finite.put_colors({Color(1, 2, 3), Color(0.5, bad, 0)});
    not_finite.put(0.5);
    write_checkpoint_file(path, not_finite.seal());
    EXPECT_EQ(checkpoint_error(path), "the checkpoint is corrupt (color 1 of 2 is not finite)") << bad;
  }
  CheckpointWriter bad_value("TEST-CHECKPOINT 1\n");
  bad_value.put_array(std::vector<double>{1, std::nan("")});
  write_checkpoint_file(path, bad_value.seal());
  try {
    CheckpointReader in(read_checkpoint_file(path), "TEST-CHECKPOINT 1\n");
    (void)in.get_doubles();
    ADD_FAILURE() << "a NaN value was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.message(), "the checkpoint is corrupt (value 1 of 2 is not finite)");
  }
}

}  // namespace
}  // namespace candela
