"""Constants of egw's piece_exp (src/egw/tables/piece_exp.inc, include/egw.h's egw_piece_exp_):
exp(x) = 2^e 2^(j/32) e^r, x = (32 e + j) ln2/32 + r, |r| <= ln2/64. Prints, from 60-digit
decimal arithmetic (Python's decimal, correctly rounded), the table 2^(j/32) = t(1 + tail)
(t the double nearest, tail the double nearest (2^(j/32) - t)/t), ln2/32 in two parts (the
high part ln 2 rounded to 36 bits, /32: k ln2_32_hi exact for |k| < 2^17), 32/ln 2 and the
Taylor coefficients 1/n!, n = 2..6, each as the shortest decimal that reads back as the
double (repr); then egw.h's form of the table (stop 58): the doubles whose bits are t's less
j 2^47, and the tails. Usage: python3 tools/reference/piece_exp_table.py"""
from decimal import Decimal as D, getcontext
from fractions import Fraction
import math
import struct

getcontext().prec = 60
ln2 = D(2).ln()
hi = D(int((ln2 * 2**36).to_integral_value())) / D(2**36)
assert D(float(hi)) == hi
print("inv_ln2_32 =", repr(float(32 / ln2)))
print("ln2_32_hi =", repr(float(hi / 32)), " (exact)")
print("ln2_32_lo =", repr(float((ln2 - hi) / 32)))
for n in range(2, 7):
    print(f"c{n} =", repr(float(Fraction(1, math.factorial(n)))))
for j in range(32):
    v = D(2) ** (D(j) / 32)
    t = float(v)
    tail = float((v - D(t)) / D(t))
    print(j, repr(t), repr(tail))

# egw.h's egw_piece_exp_core_ adds k 2^47 (z's bits shifted) to t_j's bits less j 2^47
bits = lambda x: struct.unpack("<Q", struct.pack("<d", x))[0]
double = lambda b: struct.unpack("<d", struct.pack("<Q", b))[0]
print("egw.h:", ", ".join(repr(double(bits(float(D(2) ** (D(j) / 32))) - (j << 47)))
                        for j in range(32)))
