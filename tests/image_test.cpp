// Images: PFM round trip, content hash, PNG writing.

#include "tracer/image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("accelbench_image_test_" + name)).string();
}

tracer::Image ramp(int w, int h) {
  tracer::Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img.at(x, y) = {float(x) / float(w), float(y) * 0.37f, -1.5e-7f * float(x + y)};
  return img;
}

TEST(Image, PfmRoundTripIsExact) {
  const tracer::Image img = ramp(17, 9);
  const std::string path = temp_path("ramp.pfm");
  img.write_pfm(path);
  const tracer::Image back = tracer::Image::read_pfm(path);
  EXPECT_TRUE(back == img);
  EXPECT_EQ(back.content_hash(), img.content_hash());
  std::remove(path.c_str());
}

TEST(Image, PfmTopRowIsWrittenLast) {
  // PFM stores rows bottom to top: the last float triple of the file is the top-right pixel.
  tracer::Image img(2, 2);
  img.at(1, 0) = {1.0f, 2.0f, 3.0f};
  const std::string path = temp_path("order.pfm");
  img.write_pfm(path);
  std::ifstream in(path, std::ios::binary);
  in.seekg(-12, std::ios::end);
  float last[3];
  in.read(reinterpret_cast<char*>(last), sizeof last);
  EXPECT_EQ(last[0], 1.0f);
  EXPECT_EQ(last[2], 3.0f);
  std::remove(path.c_str());
}

TEST(Image, HashSeesOneBitAndTheShape) {
  tracer::Image a = ramp(8, 8);
  const std::uint64_t h = a.content_hash();
  a.at(3, 5).y = std::nextafter(a.at(3, 5).y, 10.0f);
  EXPECT_NE(a.content_hash(), h);
  EXPECT_NE(tracer::Image(4, 2).content_hash(), tracer::Image(2, 4).content_hash());
  EXPECT_EQ(tracer::hash_hex(0x1234abcdull), "000000001234abcd");
}

TEST(Image, ReadPfmRejectsGarbage) {
  const std::string path = temp_path("bad.pfm");
  std::ofstream(path) << "P6\n2 2\n255\n";
  EXPECT_THROW(tracer::Image::read_pfm(path), std::runtime_error);
  std::ofstream(path) << "PF\n4 4\n-1.0\n0123";  // truncated data
  EXPECT_THROW(tracer::Image::read_pfm(path), std::runtime_error);
  EXPECT_THROW(tracer::Image::read_pfm(temp_path("missing.pfm")), std::runtime_error);
  std::remove(path.c_str());
}

TEST(Image, WritesAPng) {
  const std::string path = temp_path("ramp.png");
  ramp(16, 16).write_png(path, 1.0f);
  std::ifstream in(path, std::ios::binary);
  char sig[8] = {};
  in.read(sig, 8);
  EXPECT_EQ(std::string(sig + 1, 3), "PNG");
  EXPECT_THROW(ramp(4, 4).write_png("/nonexistent-dir/x.png"), std::runtime_error);
  std::remove(path.c_str());
}

TEST(Image, MeanAveragesEveryChannel) {
  tracer::Image img(2, 1);
  img.at(0, 0) = {1.0f, 2.0f, 3.0f};
  EXPECT_DOUBLE_EQ(img.mean(), 1.0);
}

}  // namespace
