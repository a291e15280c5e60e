#include "backends/format.h"

#include <cmath>

namespace clpc {

namespace {

constexpr int64_t kPow10[] = {1,          10,          100,          1000,          10000,          100000,
                              1000000,    10000000,    100000000,    1000000000,    10000000000,    100000000000,
                              1000000000000, 10000000000000, 100000000000000, 1000000000000000};

// Writes the decimal digits of u into the end of buf, returns the start.
char* digits(uint64_t u, char* end) {
  do {
    *--end = char('0' + u % 10);
    u /= 10;
  } while (u);
  return end;
}

}  // namespace

bool quantize(double value, const AddressFormat& f, int64_t& q) {
  double x = value * f.scale * double(kPow10[f.decimals]);
  if (!std::isfinite(x) || std::abs(x) >= 1e15) return false;
  q = std::llround(x);
  return true;
}

double dequantize(int64_t q, const AddressFormat& f) { return double(q) / double(kPow10[f.decimals]) / f.scale; }

void append_int(int64_t n, int width, std::string& out) {
  char buf[24];
  uint64_t u = n < 0 ? uint64_t(-(n + 1)) + 1 : uint64_t(n);
  char* s = digits(u, buf + sizeof buf);
  if (n < 0) out.push_back('-');
  for (int pad = width - int(buf + sizeof buf - s); pad > 0; --pad) out.push_back('0');
  out.append(s, buf + sizeof buf);
}

void append_quantized(int64_t q, const AddressFormat& f, std::string& out) {
  bool neg = q < 0;
  uint64_t u = neg ? uint64_t(-(q + 1)) + 1 : uint64_t(q);
  if (neg) out.push_back('-');
  else if (f.plus && u != 0) out.push_back('+');
  if (f.point == AddressFormat::Point::Never) {
    char buf[24];
    char* s = digits(u, buf + sizeof buf);
    for (int pad = f.digits - int(buf + sizeof buf - s); pad > 0; --pad) out.push_back('0');
    out.append(s, buf + sizeof buf);
    return;
  }
  const int d = f.decimals;
  uint64_t ip = u / uint64_t(kPow10[d]);
  uint64_t fp = u % uint64_t(kPow10[d]);
  char buf[24];
  char* end = buf + sizeof buf;
  if (ip != 0 || f.leading_zero || fp == 0 || f.digits > 0) {
    char* s = digits(ip, end);
    for (int pad = f.digits - int(end - s); pad > 0; --pad) out.push_back('0');
    out.append(s, end);
  }
  // Fraction: exactly d digits, then trailing zeros dropped unless kept.
  int nfrac = d;
  char frac[16];
  for (int i = d - 1; i >= 0; --i) {
    frac[i] = char('0' + fp % 10);
    fp /= 10;
  }
  if (!f.trailing_zeros)
    while (nfrac > 0 && frac[nfrac - 1] == '0') --nfrac;
  if (nfrac > 0) {
    out.push_back('.');
    out.append(frac, size_t(nfrac));
  } else if (f.point == AddressFormat::Point::Always) {
    out.push_back('.');
  }
}

}  // namespace clpc
