// Quantities with units -> SI: each accepted unit converts exactly, and wrong input says what is accepted.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "common/units.h"

namespace peensim {
namespace {

constexpr double pi = std::numbers::pi;

std::string error_of(std::string_view text, Dimension dim) {
    try {
        parse_quantity(text, dim);
    } catch (const QuantityError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(Units, LengthsConvertExactly) {
    EXPECT_EQ(parse_quantity("2 mm", Dimension::length), 2e-3);
    EXPECT_EQ(parse_quantity("2mm", Dimension::length), 2e-3);
    EXPECT_EQ(parse_quantity("25 um", Dimension::length), 25e-6);
    EXPECT_EQ(parse_quantity("25 \u00b5m", Dimension::length), 25e-6);
    EXPECT_EQ(parse_quantity("25 \u03bcm", Dimension::length), 25e-6);
    EXPECT_EQ(parse_quantity("1e-3 m", Dimension::length), 1e-3);
    EXPECT_EQ(parse_quantity("3 cm", Dimension::length), 0.03);
    EXPECT_EQ(parse_quantity("1 in", Dimension::length), 0.0254);
    EXPECT_EQ(parse_quantity("500 nm", Dimension::length), 500e-9);
    EXPECT_EQ(parse_quantity("-5 mm", Dimension::length), -5e-3);
    EXPECT_EQ(parse_quantity("+4 mm", Dimension::length), 4e-3);
    EXPECT_EQ(parse_quantity("  0.25  ", Dimension::length), 0.25);  // plain number = SI
}

// A typed -0 reads as 0 (its sign bit clear), so that the check's echo, scene.resolved.yaml and
// the files written from it say "0", not "-0".
TEST(Units, MinusZeroReadsAsZero) {
    for (const char* text : {"-0", "-0.0", "-0 mm", "-0e3 m", "  -0.000  "}) {
        EXPECT_FALSE(std::signbit(parse_quantity(text, Dimension::length))) << text;
        EXPECT_EQ(format_si(parse_quantity(text, Dimension::length)), "0") << text;
    }
    EXPECT_EQ(format_si(-0.0), "0");  // a computed -0 (a unit vector's component) too
    double plain = -1.0;
    ASSERT_TRUE(parse_plain_number("-0", plain));
    EXPECT_FALSE(std::signbit(plain));
}

TEST(Units, TimesAndFrequenciesConvertExactly) {
    EXPECT_EQ(parse_quantity("5 s", Dimension::time), 5.0);
    EXPECT_EQ(parse_quantity("50 ms", Dimension::time), 0.05);
    EXPECT_EQ(parse_quantity("20 us", Dimension::time), 20e-6);
    EXPECT_EQ(parse_quantity("2 min", Dimension::time), 120.0);
    EXPECT_EQ(parse_quantity("1 h", Dimension::time), 3600.0);
    EXPECT_EQ(parse_quantity("20 kHz", Dimension::frequency), 20000.0);
    EXPECT_EQ(parse_quantity("50 Hz", Dimension::frequency), 50.0);
    EXPECT_EQ(parse_quantity("1.5 MHz", Dimension::frequency), 1.5e6);
}

TEST(Units, SpeedsAndAccelerationsConvertExactly) {
    EXPECT_EQ(parse_quantity("1.5 m/s", Dimension::speed), 1.5);
    EXPECT_EQ(parse_quantity("250 mm/s", Dimension::speed), 0.25);
    EXPECT_EQ(parse_quantity("36 km/h", Dimension::speed), 10.0);
    EXPECT_EQ(parse_quantity("9.81 m/s2", Dimension::acceleration), 9.81);
    EXPECT_EQ(parse_quantity("9.81 m/s^2", Dimension::acceleration), 9.81);
    EXPECT_EQ(parse_quantity("9810 mm/s2", Dimension::acceleration), 9.81);
}

TEST(Units, DensitiesAndStressesConvertExactly) {
    EXPECT_EQ(parse_quantity("7.8 g/cm3", Dimension::density), 7800.0);
    EXPECT_EQ(parse_quantity("7.8 g/cm^3", Dimension::density), 7800.0);
    EXPECT_EQ(parse_quantity("7800 kg/m3", Dimension::density), 7800.0);
    EXPECT_EQ(parse_quantity("400 MPa", Dimension::stress), 400e6);
    EXPECT_EQ(parse_quantity("1.1 GPa", Dimension::stress), 1.1e9);
    EXPECT_EQ(parse_quantity("250 kPa", Dimension::stress), 250e3);
    EXPECT_EQ(parse_quantity("300 N/mm2", Dimension::stress), 300e6);
}

TEST(Units, AnglesAndAngularSpeedsConvertExactly) {
    EXPECT_EQ(parse_quantity("90 deg", Dimension::angle), pi / 2);
    EXPECT_EQ(parse_quantity("90\u00b0", Dimension::angle), pi / 2);
    EXPECT_EQ(parse_quantity("180 deg", Dimension::angle), pi);
    EXPECT_EQ(parse_quantity("0.5 rad", Dimension::angle), 0.5);
    EXPECT_EQ(parse_quantity("60 rpm", Dimension::angular_speed), 2 * pi);
    EXPECT_EQ(parse_quantity("30 rpm", Dimension::angular_speed), pi);
    EXPECT_EQ(parse_quantity("1 rev/s", Dimension::angular_speed), 2 * pi);
    EXPECT_EQ(parse_quantity("120 rev/min", Dimension::angular_speed), 4 * pi);
    EXPECT_EQ(parse_quantity("3.1 rad/s", Dimension::angular_speed), 3.1);
    EXPECT_EQ(parse_quantity("180 deg/s", Dimension::angular_speed), pi);
}

TEST(Units, PlainNumbersCanTakeAnotherUnit) {
    // Euler angles are written in degrees.
    EXPECT_EQ(parse_quantity("90", Dimension::angle, "deg"), pi / 2);
    EXPECT_EQ(parse_quantity("1 rad", Dimension::angle, "deg"), 1.0);
}

TEST(Units, UnknownUnitListsTheAcceptedOnes) {
    const std::string msg = error_of("2 mmm", Dimension::length);
    EXPECT_NE(msg.find("unknown unit 'mmm'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("a length"), std::string::npos) << msg;
    EXPECT_NE(msg.find("m, cm, mm, um"), std::string::npos) << msg;
}

TEST(Units, UnitOfAnotherDimensionIsRejected) {
    const std::string msg = error_of("2 kHz", Dimension::length);
    EXPECT_NE(msg.find("'kHz' is a unit of frequency"), std::string::npos) << msg;
    EXPECT_NE(msg.find("a length is expected"), std::string::npos) << msg;
    EXPECT_NE(msg.find("accepted units: m, cm, mm"), std::string::npos) << msg;
    EXPECT_NE(error_of("60 rpm", Dimension::frequency).find("angular speed"), std::string::npos);
    EXPECT_NE(error_of("3 mm", Dimension::dimensionless).find("a plain number (or a percentage"), std::string::npos);
}

TEST(Units, NonNumbersAreRejected) {
    for (const char* bad : {"", "mm", "abc", "inf", "nan", "-", "1e999", "two mm"}) {
        const std::string msg = error_of(bad, Dimension::length);
        EXPECT_NE(msg, "(no error)") << "'" << bad << "' was accepted";
    }
    EXPECT_NE(error_of("abc", Dimension::time).find("a time (a number in s"), std::string::npos);
}

TEST(Units, PlainNumbersParseWholeTextOnly) {
    double v = 0.0;
    EXPECT_TRUE(parse_plain_number(" -1.5e-3 ", v));
    EXPECT_EQ(v, -1.5e-3);
    EXPECT_TRUE(parse_plain_number("+4", v));
    EXPECT_EQ(v, 4.0);
    EXPECT_FALSE(parse_plain_number("4 mm", v));
    EXPECT_FALSE(parse_plain_number("nan", v));
    EXPECT_FALSE(parse_plain_number("", v));
}

TEST(Units, FormatSiReadsBackExactly) {
    EXPECT_EQ(format_si(0.002), "0.002");
    EXPECT_EQ(format_si(20000.0), "20000");
    EXPECT_EQ(format_si(-9.81), "-9.81");
    for (double v : {2 * pi, 1.0 / 3.0, 25e-6, 7800.0, -0.005, 1.1e9, 6.123233995736766e-17}) {
        double back = 0.0;
        ASSERT_TRUE(parse_plain_number(format_si(v), back)) << format_si(v);
        EXPECT_EQ(back, v) << format_si(v);
    }
}

TEST(Units, EveryDimensionNamesItsSiUnitFirst) {
    EXPECT_EQ(si_unit(Dimension::length), "m");
    EXPECT_EQ(si_unit(Dimension::acceleration), "m/s2");
    EXPECT_EQ(si_unit(Dimension::density), "kg/m3");
    EXPECT_EQ(si_unit(Dimension::angular_speed), "rad/s");
    EXPECT_EQ(si_unit(Dimension::dimensionless), "-");
    EXPECT_EQ(accepted_units(Dimension::stress).front(), "Pa");
}

}  // namespace
}  // namespace peensim
