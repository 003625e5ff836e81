// Test helper: a fixture holding the headless GL context (gpu/context.h). Where GL cannot be
// created at run time every GPU test FAILS (never skips) with the harness's one-line reason:
// the test command's setup (scripts/setup.sh) installs the packages it needs.
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "skylight/gpu/context.h"

namespace skylight::testing_support {

class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override {
    try {
      context_ = std::make_unique<gpu::Context>();
    } catch (const gpu::GpuError& e) {
      FAIL() << "no headless GL here (docs/GPU.md): " << e.what();
    }
  }
  gpu::Context& context() { return *context_; }

 private:
  std::unique_ptr<gpu::Context> context_;
};

}  // namespace skylight::testing_support
