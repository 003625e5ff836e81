#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "skylight/core/error.h"
#include "skylight/models/sky_model.h"

namespace skylight {
namespace {

TEST(Registry, UnknownModelAndBadParameters) {
  SkyParameters p;
  EXPECT_THROW(make_sky_model("nope", p), InvalidArgument);
  p.sun.zenith = std::nan("");
  EXPECT_THROW(make_sky_model("preetham", p), InvalidArgument);
  SkyParameters q;
  EXPECT_THROW(make_sky_model("perez", q), InvalidArgument) << "perez needs coefficients";
  q.values.set("perez", std::vector<double>{-1, -0.32, 10, -3, 0.45});
  EXPECT_THROW(make_sky_model("perez", q), InvalidArgument) << "perez needs a zenith luminance";
  q.values.set("zenith-luminance", 100.0);
  EXPECT_NO_THROW(make_sky_model("perez", q));
  q.values.set("perez", std::vector<double>{-2, 0.5, 0, 0, 0});  // F(0) = 1 - 2 e^0.5 < 0
  EXPECT_THROW(make_sky_model("perez", q), InvalidArgument);
  for (const auto& info : model_registry()) {
    EXPECT_FALSE(info.parameters.empty()) << info.name;
    for (const auto& par : info.parameters)
      EXPECT_LE(par.min, par.max) << info.name << " " << par.name;
  }
}

TEST(Registry, EveryParameterHasAUsableSpec) {
  for (const auto& info : model_registry()) {
    for (const auto& p : all_parameters(info)) {
      EXPECT_FALSE(p.description.empty()) << info.name << " " << p.name;
      EXPECT_EQ(p.name.find_first_of(" _="), std::string::npos) << p.name;
      // A typed default lies in the range.
      if (const auto* v = std::get_if<ParameterValue>(&p.default_value)) {
        EXPECT_NO_THROW(p.check(*v)) << info.name << " " << p.name;
      }
    }
    // The defaults (and the example values for required parameters) build the model.
    SkyParameters sp;
    sp.values = info.example;
    EXPECT_NO_THROW(info.make(sp)) << info.name;
  }
}

TEST(Registry, ModelsReportWhatTheyReadAsParameterValues) {
  for (const auto& info : model_registry()) {
    SkyParameters sp;
    sp.values = info.example;
    const auto m = info.make(sp);
    const ParameterValues read = m->parameter_values();
    for (const auto& [name, value] : read.all()) {
      const auto it = std::find_if(info.parameters.begin(), info.parameters.end(),
                                   [&](const ParameterSpec& s) { return s.name == name; });
      ASSERT_NE(it, info.parameters.end()) << info.name << " reports '" << name << "'";
      EXPECT_NO_THROW(it->check(value)) << info.name << " " << name;
    }
    // Feeding them back builds the same sky.
    SkyParameters again;
    again.values = read;
    const auto m2 = info.make(again);
    const Vec3 v = direction_from_angles(1.0, 2.0);
    EXPECT_EQ(m2->tristimulus(v).Y, m->tristimulus(v).Y) << info.name;
  }
}

// docs/MODELS.md shows each model's parameter table as generated from the schema; a change of
// either without the other fails here (regenerate with `skylight models --markdown`).
TEST(Registry, DocsParameterTablesMatchTheSchema) {
  std::ifstream in(std::string(SKYLIGHT_SOURCE_DIR) + "/docs/MODELS.md");
  ASSERT_TRUE(in) << "docs/MODELS.md not found";
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string doc = ss.str();
  for (const auto& info : model_registry()) {
    const std::string block = parameter_docs_block(info);
    EXPECT_NE(doc.find(block), std::string::npos)
        << "docs/MODELS.md lacks this table of '" << info.name << "':\n"
        << block;
  }
}

}  // namespace
}  // namespace skylight
