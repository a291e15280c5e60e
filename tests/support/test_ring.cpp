// support/ring.h: verify's window of program segments. Order kept across wrap-around and
// growth; slots reused.
#include "support/ring.h"

#include <gtest/gtest.h>

#include <string>

namespace clpc {
namespace {

TEST(Ring, KeepsOrderAcrossWrapAroundAndGrowth) {
  Ring<std::string> r;
  int next_in = 0, next_out = 0;
  // Slide a window of 10 over 100 elements (wraps the 16 slots many times), then grow it to 40
  // while it is wrapped, then drain.
  for (; next_in < 10; ++next_in) r.push_back_slot() = std::to_string(next_in);
  for (int k = 0; k < 100; ++k) {
    r.push_back_slot() = std::to_string(next_in++);
    EXPECT_EQ(r.front(), std::to_string(next_out++));
    r.pop_front();
  }
  ASSERT_EQ(r.size(), 10u);
  for (int k = 0; k < 30; ++k) r.push_back_slot() = std::to_string(next_in++);
  ASSERT_EQ(r.size(), 40u);
  for (size_t i = 0; i < r.size(); ++i) EXPECT_EQ(r[i], std::to_string(next_out + int(i)));
  while (!r.empty()) {
    EXPECT_EQ(r.front(), std::to_string(next_out++));
    r.pop_front();
  }
  EXPECT_EQ(next_out, next_in);
}

TEST(Ring, PopBackGivesTheSlotBack) {
  Ring<int> r;
  r.push_back_slot() = 1;
  r.push_back_slot() = 2;
  r.pop_back();  // a read that found nothing
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], 1);
  r.push_back_slot() = 3;
  EXPECT_EQ(r[1], 3);
}

}  // namespace
}  // namespace clpc
