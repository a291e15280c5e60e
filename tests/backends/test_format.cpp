// Number formats (integer arithmetic) and the emitter's words, modal suppression, numbering
// and comments.
#include "backends/emitter.h"
#include "machine/format.h"
#include "helpers.h"

using namespace clpc;
using namespace clpc::test;

namespace {

std::string fmt(double v, AddressFormat f) {
  int64_t q;
  if (!quantize(v, f, q)) return "<range>";
  std::string s;
  append_quantized(q, f, s);
  return s;
}

AddressFormat decimals(int d) {
  AddressFormat f;
  f.decimals = d;
  return f;
}

}  // namespace

TEST(Format, DecimalPointAlwaysTrailingZerosDropped) {
  AddressFormat f = decimals(4);
  EXPECT_EQ(fmt(1.5, f), "1.5");
  EXPECT_EQ(fmt(2, f), "2.");
  EXPECT_EQ(fmt(0, f), "0.");
  EXPECT_EQ(fmt(-0.0, f), "0.");
  EXPECT_EQ(fmt(-0.00004, f), "0.");  // rounds to zero: no "-0."
  EXPECT_EQ(fmt(-0.00005, f), "-0.0001");
  EXPECT_EQ(fmt(123.456789, f), "123.4568");
  EXPECT_EQ(fmt(-12.3, f), "-12.3");
}

TEST(Format, LeadingZeroSuppressed) {
  AddressFormat f = decimals(3);
  f.leading_zero = false;
  EXPECT_EQ(fmt(0.5, f), ".5");
  EXPECT_EQ(fmt(-0.25, f), "-.25");
  EXPECT_EQ(fmt(0, f), "0.");
  EXPECT_EQ(fmt(3.5, f), "3.5");
}

TEST(Format, TrailingZerosKept) {
  AddressFormat f = decimals(3);
  f.trailing_zeros = true;
  EXPECT_EQ(fmt(1.5, f), "1.500");
  EXPECT_EQ(fmt(2, f), "2.000");
}

TEST(Format, PointNeverIsLeastInputIncrements) {
  AddressFormat f = decimals(3);
  f.point = AddressFormat::Point::Never;
  EXPECT_EQ(fmt(12.5, f), "12500");
  EXPECT_EQ(fmt(-0.002, f), "-2");
  AddressFormat t;
  t.decimals = 0;
  t.point = AddressFormat::Point::Never;
  t.digits = 2;
  EXPECT_EQ(fmt(3, t), "03");
  t.digits = 5;
  EXPECT_EQ(fmt(1234, t), "01234");
}

TEST(Format, PointIfFraction) {
  AddressFormat f = decimals(2);
  f.point = AddressFormat::Point::IfFraction;
  EXPECT_EQ(fmt(100, f), "100");
  EXPECT_EQ(fmt(100.25, f), "100.25");
}

TEST(Format, ScaleAndPlus) {
  AddressFormat f = decimals(3);
  f.scale = 2;  // lathe diameter
  EXPECT_EQ(fmt(1.25, f), "2.5");
  f.plus = true;
  EXPECT_EQ(fmt(1.25, f), "+2.5");
  EXPECT_EQ(fmt(0, f), "0.");
}

TEST(Format, RoundingAndRange) {
  AddressFormat f = decimals(4);
  EXPECT_EQ(fmt(0.00005, f), "0.0001");  // half away from zero
  EXPECT_EQ(fmt(1e20, f), "<range>");
  EXPECT_EQ(fmt(std::nan(""), f), "<range>");
  EXPECT_DOUBLE_EQ(dequantize(12345, f), 1.2345);
}

TEST(Format, IntegersPadded) {
  std::string s;
  append_int(7, 3, s);
  append_int(-12, 0, s);
  EXPECT_EQ(s, "007-12");
}

namespace {

// Emits blocks for a machine into a string.
struct Harness {
  Machine m;
  TempDir dir;
  OutputFile out;
  std::ostringstream err;
  Diagnostics d{&err};
  std::unique_ptr<Emitter> e;
  explicit Harness(Machine mm) : m(std::move(mm)) {
    std::string why;
    out.open(dir.path("o.nc"), why);
    e = std::make_unique<Emitter>(m, out, d);
  }
  std::string text() {
    std::string why;
    out.commit(why);
    return read_file(dir.path("o.nc"));
  }
};

}  // namespace

TEST(Emitter, ModalWordsAndSequenceNumbers) {
  Machine m = default_machine(Family::Mill, ir::Units::Mm);
  m.sequence.start = 10;
  m.sequence.step = 5;
  Harness h(m);
  h.e->begin({});
  h.e->modal_word('X', 1.0);
  h.e->modal_word('Y', 2.0);
  h.e->end();
  h.e->begin({});
  h.e->modal_word('X', 1.0004);  // rounds to the same 1.000: dropped
  h.e->modal_word('Y', 3.0);
  h.e->end();
  h.e->begin({});
  h.e->modal_word('X', 1.0);
  h.e->end();  // empty block: nothing written, no number used
  h.e->begin({});
  h.e->word('X', 1.0);
  h.e->end();
  EXPECT_EQ(h.text(), "N10 X1. Y2.\nN15 Y3.\nN20 X1.\n");
}

TEST(Emitter, SequenceWrapAndToolChangeOnly) {
  Machine m = default_machine(Family::Mill, ir::Units::Mm);
  m.sequence.start = 98;
  m.sequence.step = 1;
  m.sequence.max = 99;
  m.sequence.wrap_to = 1;
  Harness h(m);
  for (int i = 0; i < 3; ++i) {
    h.e->begin({});
    h.e->word('G', 0);
    h.e->end();
  }
  EXPECT_EQ(h.text(), "N98 G0\nN99 G0\nN1 G0\n");

  Machine t = default_machine(Family::Mill, ir::Units::Mm);
  t.sequence.tool_change_only = true;
  Harness h2(t);
  h2.e->begin({});
  h2.e->word('X', 1);
  h2.e->end();
  h2.e->begin({});
  h2.e->word('T', 1);
  h2.e->end(true);
  EXPECT_EQ(h2.text(), "X1.\nN10 T1\n");
}

TEST(Emitter, SeparatorBlockEndAndCodes) {
  Machine m = default_machine(Family::Mill, ir::Units::Mm);
  m.separator = "";
  m.block_end = ";";
  m.sequence.enabled = false;
  Harness h(m);
  CodeTemplate t;
  std::string why;
  ASSERT_TRUE(parse_template("T{tool} M06", t, why));
  h.e->begin({});
  h.e->code(t, TemplateVars().with(Var::Tool, 12));
  h.e->word('X', -1.5);
  h.e->end();
  EXPECT_EQ(h.text(), "T12M06X-1.5;\n");
}

TEST(Emitter, TemplateWidthsAndAddressFormats) {
  Machine m = default_machine(Family::Lathe, ir::Units::Mm);
  m.sequence.enabled = false;
  Harness h(m);
  CodeTemplate t, p;
  std::string why;
  ASSERT_TRUE(parse_template("T{tool:2}{offset:2} G04 P{milliseconds:1} U{seconds}", t, why));
  h.e->begin({});
  h.e->code(t, TemplateVars().with(Var::Tool, 3).with(Var::Offset, 13).with(Var::Milliseconds, 1500).with(Var::Seconds, 1.5));
  h.e->end();
  EXPECT_EQ(h.text(), "T0313 G04 P1500 U1.5\n");
}

TEST(Emitter, TemplateErrors) {
  CodeTemplate t;
  std::string why;
  EXPECT_FALSE(parse_template("T{toll}", t, why));
  EXPECT_EQ(why, "unknown placeholder {toll}");
  EXPECT_FALSE(parse_template("T{tool", t, why));
  EXPECT_EQ(why, "'{' without '}'");
  EXPECT_FALSE(parse_template("T{tool:x}", t, why));
  EXPECT_EQ(why, "width in {tool:x} must be a digit 1-9");
}

TEST(Emitter, CommentsCleanedAndLimited) {
  Machine m = default_machine(Family::Mill, ir::Units::Mm);
  m.comments.max_length = 12;
  Harness h(m);
  h.e->comment("rough (side) \x01 f\xc3\xa4sen");
  h.e->comment("");
  EXPECT_EQ(h.text(), "(ROUGH SIDE F)\n");
  EXPECT_EQ(h.e->clean_comment("a(b)c"), "A B C");
  Machine off = default_machine(Family::Mill, ir::Units::Mm);
  off.comments.enabled = false;
  Harness h2(off);
  h2.e->comment("x");
  EXPECT_EQ(h2.text(), "");
}
