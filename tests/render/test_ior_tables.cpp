#include <gtest/gtest.h>

#include "quadtri/math/error.h"
#include "quadtri/render/bsdf/ior_tables.h"

namespace quadtri {
namespace {

TEST(IorTables, NamedMediaHaveMitsubasValues) {
  EXPECT_EQ(lookupIor("bk7"), 1.5046);
  EXPECT_EQ(lookupIor("BK7"), 1.5046);  // Mitsuba matches names case-insensitively
  EXPECT_EQ(lookupIor("vacuum"), 1.0);
  EXPECT_EQ(lookupIor("air"), 1.000277);
  EXPECT_EQ(lookupIor("water"), 1.3330);
  EXPECT_EQ(lookupIor("acrylic glass"), 1.49);
  EXPECT_EQ(lookupIor("polypropylene"), 1.49);
  EXPECT_EQ(lookupIor("diamond"), 2.419);
  for (const std::string& name : iorNames()) {
    EXPECT_GE(lookupIor(name), 1.0) << name;
    EXPECT_LT(lookupIor(name), 2.5) << name;
  }
}

TEST(IorTables, UnknownNamesListTheValidOnes) {
  try {
    lookupIor("unobtainium");
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("unobtainium"), std::string::npos) << message;
    EXPECT_NE(message.find("bk7"), std::string::npos) << message;
    EXPECT_NE(message.find("diamond"), std::string::npos) << message;
  }
  try {
    lookupConductor("Kryptonite");
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("Kryptonite"), std::string::npos) << message;
    for (const char* name : {"Au", "Ag", "Cu", "Al", "Cr", "none"})
      EXPECT_NE(message.find(name), std::string::npos) << message;
  }
}

TEST(IorTables, ConductorPresets) {
  const ConductorIor au = lookupConductor("Au");
  EXPECT_EQ(au.eta[0], 0.1431189557);
  EXPECT_EQ(au.k[2], 1.6032152899);
  for (const std::string& name : conductorNames()) {
    const ConductorIor ior = lookupConductor(name);
    EXPECT_TRUE((ior.eta >= 0.0).all() && (ior.k > 0.0).all()) << name;
  }
}

}  // namespace
}  // namespace quadtri
