#include "machine/format.h"

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

double dequantize(int64_t q, const AddressFormat& f) { return double(q) / double(kPow10[f.decimals]) / f.scale; }

double as_written(double value, const AddressFormat& f) {
  int64_t q;
  return quantize(value, f, q) ? dequantize(q, f) : std::nan("");
}

void append_int(int64_t n, int width, std::string& out) {
  char buf[24];
  uint64_t u = n < 0 ? uint64_t(-(n + 1)) + 1 : uint64_t(n);
  char* s = digits(u, buf + sizeof buf);
  if (n < 0) out.push_back('-');
  for (int pad = width - int(buf + sizeof buf - s); pad > 0; --pad) out.push_back('0');
  out.append(s, buf + sizeof buf);
}

void append_quantized(int64_t q, const AddressFormat& f, std::string& out) {
  // Built right to left in a small buffer, appended once.
  char buf[48];
  char* const end = buf + sizeof buf;
  char* p = end;
  const bool neg = q < 0;
  uint64_t u = neg ? uint64_t(-(q + 1)) + 1 : uint64_t(q);
  if (f.point == AddressFormat::Point::Never) {
    p = digits(u, p);
    for (int pad = f.digits - int(end - p); pad > 0 && p > buf + 2; --pad) *--p = '0';
  } else {
    const int d = f.decimals;
    const uint64_t ip = u / uint64_t(kPow10[d]);
    uint64_t fp = u % uint64_t(kPow10[d]);
    const bool whole = fp == 0;
    // Fraction: d digits less the trailing zeros (unless kept), after a point.
    int nfrac = d;
    if (!f.trailing_zeros)
      while (nfrac > 0 && fp % 10 == 0) {
        fp /= 10;
        --nfrac;
      }
    for (int i = 0; i < nfrac; ++i) {
      *--p = char('0' + fp % 10);
      fp /= 10;
    }
    if (nfrac > 0 || f.point == AddressFormat::Point::Always) *--p = '.';
    if (ip != 0 || f.leading_zero || whole || f.digits > 0) {
      char* int_end = p;
      p = digits(ip, p);
      for (int pad = f.digits - int(int_end - p); pad > 0 && p > buf + 2; --pad) *--p = '0';
    }
  }
  if (neg) *--p = '-';
  else if (f.plus && u != 0) *--p = '+';
  out.append(p, size_t(end - p));
}

}  // namespace clpc
