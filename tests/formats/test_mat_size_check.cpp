// checkMatSizes: MAT-file v5 sizes checked before libmatio allocates from them.
#include <gtest/gtest.h>

#include <zlib.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "formats/mat_fixture.hpp"
#include "formats/mat_size_check.hpp"
#include "common/temp_dir.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap {
namespace {

using Bytes = std::vector<unsigned char>;

Bytes readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), {});
}

/// The FileError message of checking `bytes`, or "" when they pass.
std::string errorOf(const Bytes& bytes) {
  try {
    detail::checkMatSizes(bytes, "t.mat");
  } catch (const FileError& e) {
    return e.what();
  }
  return "";
}

void putU32(Bytes& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>((v >> (8 * i)) & 0xFFU));
}

/// A 128-byte little-endian header and one uncompressed array: class `cls`, dimensions `dims`,
/// name "v", then `payload` zero bytes after `fields` (a struct's field name length and names).
Bytes fileWithArray(std::uint32_t cls, std::vector<std::int32_t> dims, std::size_t payload, const Bytes& fields = {}) {
  Bytes array;
  putU32(array, 6), putU32(array, 8), putU32(array, cls), putU32(array, 0);  // array flags
  putU32(array, 5), putU32(array, static_cast<std::uint32_t>(4 * dims.size()));
  for (const std::int32_t d : dims) putU32(array, static_cast<std::uint32_t>(d));
  while (array.size() % 8 != 0) array.push_back(0);
  putU32(array, (1U << 16) | 1U), array.push_back('v'), array.resize(array.size() + 3, 0);  // small name
  array.insert(array.end(), fields.begin(), fields.end());
  array.resize(array.size() + payload, 0);
  Bytes file(128, ' ');
  file[124] = 0x00, file[125] = 0x01, file[126] = 'I', file[127] = 'M';
  putU32(file, 14), putU32(file, static_cast<std::uint32_t>(array.size()));
  file.insert(file.end(), array.begin(), array.end());
  return file;
}

TEST(sonarMatSizeCheck, AcceptsFilesLibmatioWrites) {
  test::TempDir dir;
  const std::string path = dir.file("ok.mat");
  test::writeCrasMat(path, std::vector<test::MatBeam>(5));
  EXPECT_EQ(errorOf(readAll(path)), "");
}

TEST(sonarMatSizeCheck, AcceptsTheCrasLog) {
  const std::string path = std::string(SONARMAP_SHARED_DATA) + "/cras_micron_tank_static.mat";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
  EXPECT_EQ(errorOf(readAll(path)), "");  // a compressed struct array of 5,603 beams
}

TEST(sonarMatSizeCheck, RejectsDimensionsTheBytesCannotHold) {
  EXPECT_EQ(errorOf(fileWithArray(6, {1, 16}, 16)), "");       // 16 elements in 16 bytes: plausible
  const std::string huge = errorOf(fileWithArray(6, {1 << 24, 1 << 24}, 16));
  EXPECT_NE(huge.find("t.mat: byte "), std::string::npos) << huge;
  EXPECT_NE(huge.find("declares 281474976710656 elements"), std::string::npos) << huge;
  Bytes two_fields;  // field name length 8 (small element), then 16 bytes of names
  putU32(two_fields, (4U << 16) | 5U), putU32(two_fields, 8), putU32(two_fields, 1), putU32(two_fields, 16);
  two_fields.resize(two_fields.size() + 16, 'a');
  EXPECT_NE(errorOf(fileWithArray(2, {1, 1000}, 16, two_fields)).find("struct elements"), std::string::npos);
  Bytes ragged_names = two_fields;  // 13 bytes of names for names of 8: libmatio would read 8
  ragged_names[12] = 13;
  EXPECT_NE(errorOf(fileWithArray(2, {1, 1}, 16, ragged_names)).find("multiple of the name length 8"), std::string::npos);
  EXPECT_NE(errorOf(fileWithArray(1, {1, 1000}, 16)).find("cells"), std::string::npos);
  EXPECT_NE(errorOf(fileWithArray(6, {1, -3}, 16)).find("is -3, expected ≥ 0"), std::string::npos);
  Bytes data_tag;  // a uint8 data subelement declaring 2^32 − 10 bytes inside a 16-byte array
  putU32(data_tag, 2), putU32(data_tag, 0xFFFFFFF6U);
  const std::string overlong = errorOf(fileWithArray(6, {1, 2}, 8, data_tag));
  EXPECT_NE(overlong.find("data element declares 4294967286 bytes"), std::string::npos) << overlong;
}

TEST(sonarMatSizeCheck, ReturnsTheElementAFileIsCutInAndRejectsBrokenCompression) {
  Bytes ok = fileWithArray(6, {1, 16}, 16);
  EXPECT_EQ(errorOf(Bytes(ok.begin(), ok.begin() + 100)), "");  // no v5 header: left to the reader
  Bytes v73 = ok;
  v73[125] = 0x02;  // version 0x0200: HDF5 inside, not walked
  EXPECT_EQ(errorOf(Bytes(v73.begin(), v73.end() - 8)), "");
  // A file cut short is no error here: the element it ends in is returned for the reader.
  const Bytes cut(ok.begin(), ok.end() - 8);
  EXPECT_EQ(errorOf(cut), "");
  const std::optional<detail::MatCut> found = detail::checkMatSizes(cut, "t.mat");
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(found->at, 128u);
  EXPECT_FALSE(found->compressed);
  EXPECT_EQ(found->element.size(), cut.size() - 128);
  EXPECT_NE(found->what.find("t.mat: byte 128: data element declares"), std::string::npos) << found->what;
  Bytes broken(ok.begin(), ok.begin() + 128);
  putU32(broken, 15), putU32(broken, 6);
  broken.insert(broken.end(), {0x78, 0x9C, 0xFF, 0xFF, 0xFF, 0xFF});  // zlib header, then garbage
  EXPECT_NE(errorOf(broken).find("does not inflate"), std::string::npos) << errorOf(broken);
}

TEST(sonarMatSizeCheck, ChecksInsideCompressedVariables) {
  const Bytes plain = fileWithArray(6, {1 << 24, 1 << 24}, 16);
  const Bytes element(plain.begin() + 128, plain.end());
  uLongf size = compressBound(static_cast<uLong>(element.size()));
  Bytes packed(size);
  ASSERT_EQ(compress(packed.data(), &size, element.data(), static_cast<uLong>(element.size())), Z_OK);
  packed.resize(size);
  Bytes file(plain.begin(), plain.begin() + 128);
  putU32(file, 15), putU32(file, static_cast<std::uint32_t>(packed.size()));
  file.insert(file.end(), packed.begin(), packed.end());
  const std::string message = errorOf(file);
  EXPECT_NE(message.find("variable compressed at byte 128, inflated"), std::string::npos) << message;
  EXPECT_NE(message.find("elements"), std::string::npos) << message;
}

TEST(sonarMatSizeCheck, GivesACompressedFileAsTheSameFileUncompressed) {
  test::TempDir dir;
  const std::vector<const char*> fields = {"time", "angle", "step_dist", "intensities"};
  test::writeCrasMat(dir.file("z.mat"), std::vector<test::MatBeam>(5), fields, "parsedData", MAT_COMPRESSION_ZLIB);
  test::writeCrasMat(dir.file("plain.mat"), std::vector<test::MatBeam>(5), fields, "parsedData", MAT_COMPRESSION_NONE);
  Bytes copy{1, 2, 3};
  EXPECT_FALSE(detail::checkMatSizes(readAll(dir.file("plain.mat")), "plain.mat", &copy));
  EXPECT_TRUE(copy.empty());  // nothing compressed: the original is read
  EXPECT_FALSE(detail::checkMatSizes(readAll(dir.file("z.mat")), "z.mat", &copy));
  ASSERT_GT(copy.size(), 128u);
  // The inflated copy is the uncompressed file libmatio writes, header aside (its text has a date).
  const Bytes plain = readAll(dir.file("plain.mat"));
  EXPECT_EQ(Bytes(copy.begin() + 128, copy.end()), Bytes(plain.begin() + 128, plain.end()));
  Bytes again{1};
  EXPECT_FALSE(detail::checkMatSizes(copy, "copy", &again));
  EXPECT_TRUE(again.empty());
}

}  // namespace
}  // namespace sonarmap
