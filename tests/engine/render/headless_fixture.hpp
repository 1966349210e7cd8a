// One headless renderer shared by a test suite; the suite skips (with EGL's reason) only when no
// EGL context can be made at all, e.g. Mesa's EGL is not installed.
#pragma once

#include <gtest/gtest.h>
#include <memory>
#include <stdexcept>
#include <string>

#include "synthetic_frames.hpp"
#include "tacta/render/headless.hpp"

namespace tacta::render::testing {

class HeadlessTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    try {
      renderer_ =
          std::make_unique<HeadlessRenderer>(HeadlessOptions{kGoldenWidth, kGoldenHeight, true});
    } catch (const std::runtime_error& e) {
      skip_reason_ = e.what();
    }
  }
  static void TearDownTestSuite() { renderer_.reset(); }
  void SetUp() override {
    if (!renderer_) GTEST_SKIP() << "no EGL context: " << skip_reason_;
  }
  static HeadlessRenderer& renderer() { return *renderer_; }

 private:
  static inline std::unique_ptr<HeadlessRenderer> renderer_;
  static inline std::string skip_reason_;
};

}  // namespace tacta::render::testing
