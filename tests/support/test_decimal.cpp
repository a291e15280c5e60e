// read_decimal must give exactly what std::from_chars gives: the same double (bit for bit,
// the sign of zero included), the same end and the same error, for every form CL and G-code
// files write and for the forms it hands to from_chars.
#include <gtest/gtest.h>

#include <charconv>
#include <cstring>
#include <random>
#include <string>

#include "support/decimal.h"

using namespace clpc;

namespace {

void same_as_from_chars(const std::string& s) {
  double a = 12345, b = 12345;
  auto ra = read_decimal(s.data(), s.data() + s.size(), a);
  auto rb = std::from_chars(s.data(), s.data() + s.size(), b);
  ASSERT_EQ(ra.ec, rb.ec) << s;
  ASSERT_EQ(ra.ptr, rb.ptr) << s;
  ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << s << ": " << a << " vs " << b;
}

}  // namespace

TEST(Decimal, TheFormsFilesWriteReadAsFromCharsReadsThem) {
  for (const char* s : {"0", "-0", "-0.0", "5.", "-5.", ".25", "-.25", "0.1", "0.3", "123.4567", "-8.8609", "1e3",
                        "1.5E-3", "", "-", ".", "abc", "12,5", "7.1.2", "0000012.500000", "999999999999999",
                        "9999999999999999", "1234567890.12345", "0.0000000000000000000001", "1.00000000000000000000001",
                        "inf", "nan", "1e400", "4.9e-324", "2.7596 Y", "103.3081,41"})
    same_as_from_chars(s);
}

TEST(Decimal, RandomDecimalsReadAsFromCharsReadsThem) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 200000; ++i) {
    std::string s;
    if (rng() % 3 == 0) s += '-';
    const int whole = int(rng() % 12), frac = int(rng() % 12);
    for (int k = 0; k < whole; ++k) s += char('0' + rng() % 10);
    if (rng() % 5) s += '.';
    for (int k = 0; k < frac; ++k) s += char('0' + rng() % 10);
    same_as_from_chars(s);
  }
}
