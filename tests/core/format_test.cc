// FormatNumber: the shortest text that reads back as the same double, so messages quote a
// value the user typed as typed.
#include "core/format.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace moorsim {
namespace {

TEST(FormatNumberTest, QuotesTypedValuesAsTyped) {
  EXPECT_EQ(FormatNumber(9.81), "9.81");
  EXPECT_EQ(FormatNumber(0.1), "0.1");
  EXPECT_EQ(FormatNumber(-0.08), "-0.08");
  EXPECT_EQ(FormatNumber(1025.0), "1025");
  EXPECT_EQ(FormatNumber(0.3333333), "0.3333333");
}

TEST(FormatNumberTest, WritesIntegersWithoutDecimals) {
  EXPECT_EQ(FormatNumber(0.0), "0");
  EXPECT_EQ(FormatNumber(1.0), "1");
  EXPECT_EQ(FormatNumber(120.0), "120");
  EXPECT_EQ(FormatNumber(-3600.0), "-3600");
  EXPECT_EQ(FormatNumber(10000.0), "10000");
}

TEST(FormatNumberTest, UsesAnExponentWhereThatIsShorter) {
  EXPECT_EQ(FormatNumber(1e9), "1e+09");
  EXPECT_EQ(FormatNumber(3.0e6), "3e+06");
  EXPECT_EQ(FormatNumber(2.5e-5), "2.5e-05");
  EXPECT_EQ(FormatNumber(1e300), "1e+300");
  EXPECT_EQ(FormatNumber(-1.5e-300), "-1.5e-300");
  EXPECT_EQ(FormatNumber(123456789.0), "123456789");
}

TEST(FormatNumberTest, KeepsTheSignOfNegativeZero) { EXPECT_EQ(FormatNumber(-0.0), "-0"); }

TEST(FormatNumberTest, NamesValuesThatAreNotFinite) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(FormatNumber(inf), "inf");
  EXPECT_EQ(FormatNumber(-inf), "-inf");
  EXPECT_EQ(FormatNumber(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(FormatNumber(-std::numeric_limits<double>::quiet_NaN()), "nan");
}

TEST(FormatNumberTest, ReadsBackAsTheSameDouble) {
  const std::vector<double> values = {0.1 + 0.2,
                                      1.0 / 3.0,
                                      2.0 / 3.0,
                                      std::sqrt(2.0),
                                      -std::acos(-1.0),
                                      9.81,
                                      1e23,
                                      std::numeric_limits<double>::min(),
                                      std::numeric_limits<double>::max(),
                                      std::numeric_limits<double>::lowest(),
                                      0x1.0p53 + 2.0};
  for (double x : values) {
    const std::string text = FormatNumber(x);
    SCOPED_TRACE(text);
    EXPECT_EQ(std::stod(text), x);
  }
  EXPECT_EQ(FormatNumber(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(FormatNumber(1.0 / 3.0), "0.3333333333333333");
}

}  // namespace
}  // namespace moorsim
