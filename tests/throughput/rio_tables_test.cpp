// Every cell of the 1747-SN appendix A tables, read back through the lookup
// functions. Expected figures are copied from the manual
// (seeds/000_6bdfccac32889807.txt, appendix A "Specifications"); each test
// names the table it checks.
#include <gtest/gtest.h>

#include <stdexcept>

#include "modules/throughput/rio_throughput.h"

namespace softslc::throughput {
namespace {

constexpr RioBaud k57 = RioBaud::b57_6k;
constexpr RioBaud k115 = RioBaud::b115_2k;
constexpr RioBaud k230 = RioBaud::b230_4k;

// Appendix A, "RIO Scan Time Calculation (T_RIO)", table "RIO Scan Times for
// Adapters" (page A-4): all twelve cells.
TEST(RioScanTimeTable, EveryAdapterSizeAtEveryBaudRate) {
    // 1/4 logical rack: 6.0 ms, 3.5 ms, 2.5 ms
    EXPECT_EQ(rio_scan_time(k57, 2), 6000);
    EXPECT_EQ(rio_scan_time(k115, 2), 3500);
    EXPECT_EQ(rio_scan_time(k230, 2), 2500);
    // 1/2 logical rack: 6.5 ms, 4.0 ms, 2.75 ms
    EXPECT_EQ(rio_scan_time(k57, 4), 6500);
    EXPECT_EQ(rio_scan_time(k115, 4), 4000);
    EXPECT_EQ(rio_scan_time(k230, 4), 2750);
    // 3/4 logical rack: 7.5 ms, 4.5 ms, 3.0 ms
    EXPECT_EQ(rio_scan_time(k57, 6), 7500);
    EXPECT_EQ(rio_scan_time(k115, 6), 4500);
    EXPECT_EQ(rio_scan_time(k230, 6), 3000);
    // Full logical rack: 9.5 ms, 5.5 ms, 3.5 ms
    EXPECT_EQ(rio_scan_time(k57, 8), 9500);
    EXPECT_EQ(rio_scan_time(k115, 8), 5500);
    EXPECT_EQ(rio_scan_time(k230, 8), 3500);
}

// The T_RIO table has rows for 1/4, 1/2, 3/4 and full racks only.
TEST(RioScanTimeTable, RejectsSizesTheTableDoesNotHave) {
    EXPECT_THROW(rio_scan_time(k57, 0), std::invalid_argument);
    EXPECT_THROW(rio_scan_time(k57, 3), std::invalid_argument);
    EXPECT_THROW(rio_scan_time(k57, 10), std::invalid_argument);
}

// Table A.1 baud rates; the T_RIO table's size rows.
TEST(RioLabels, BaudModeAndSizeNamesRoundTrip) {
    for (RioBaud baud : {k57, k115, k230}) EXPECT_EQ(parse_rio_baud(to_string(baud)), baud);
    EXPECT_EQ(to_string(k115), "115.2K");
    EXPECT_FALSE(parse_rio_baud("115.2k"));
    EXPECT_FALSE(parse_rio_baud("19.2K"));
    EXPECT_EQ(parse_rio_mode("complementary"), RioMode::complementary);
    EXPECT_FALSE(parse_rio_mode("primary"));
    for (int groups : {2, 4, 6, 8}) EXPECT_EQ(groups_for_rack_size(rack_size_label(groups)), groups);
    EXPECT_EQ(rack_size_label(8), "full");
    EXPECT_FALSE(groups_for_rack_size("1/8"));
}

// Checks one T_SNO cell: "T_SNO if T_upd <= T_hold | T_hold | T_SNO if T_upd > T_hold".
void expect_cell(TsnoTable table, RioMode mode, RioBaud baud, int racks, Micros le, Micros hold, Micros gt) {
    const TsnoCell cell = t_sno_cell(table, mode, baud, racks);
    EXPECT_EQ(cell.if_upd_le_hold, le) << racks << " racks, " << to_string(baud);
    EXPECT_EQ(cell.t_hold, hold) << racks << " racks, " << to_string(baud);
    EXPECT_EQ(cell.if_upd_gt_hold, gt) << racks << " racks, " << to_string(baud);
}

// Appendix A, "T_SNO without M0 File Writes", Normal Mode table (page A-14):
// one column for all baud rates.
TEST(RioTsnoTable, WithoutM0WritesNormalModeAllBaudRates) {
    for (RioBaud baud : {k57, k115, k230}) {
        expect_cell(TsnoTable::without_m0_writes, RioMode::normal, baud, 1, 5000, 5000, 2500);
        expect_cell(TsnoTable::without_m0_writes, RioMode::normal, baud, 2, 7000, 7000, 4000);
        expect_cell(TsnoTable::without_m0_writes, RioMode::normal, baud, 3, 9000, 9000, 5500);
        expect_cell(TsnoTable::without_m0_writes, RioMode::normal, baud, 4, 11000, 11000, 7000);
    }
}

// Appendix A, "T_SNO without M0 File Writes", Complementary table.
TEST(RioTsnoTable, WithoutM0WritesComplementaryMode) {
    const auto t = TsnoTable::without_m0_writes;
    const auto c = RioMode::complementary;
    expect_cell(t, c, k57, 1, 6000, 5000, 4000);
    expect_cell(t, c, k57, 2, 9000, 8000, 5000);
    expect_cell(t, c, k57, 3, 12000, 11000, 7000);
    expect_cell(t, c, k57, 4, 15000, 14000, 9000);
    expect_cell(t, c, k115, 1, 7000, 7000, 4000);
    expect_cell(t, c, k115, 2, 10000, 10000, 6000);
    expect_cell(t, c, k115, 3, 12000, 12000, 8000);
    expect_cell(t, c, k115, 4, 16000, 16000, 10000);
    expect_cell(t, c, k230, 1, 10000, 9000, 4000);
    expect_cell(t, c, k230, 2, 12000, 12000, 7000);
    expect_cell(t, c, k230, 3, 16000, 16000, 10000);
    // The manual prints T_hold 22.0 beside T_SNO 21.0 here; it is kept as printed.
    expect_cell(t, c, k230, 4, 21000, 22000, 13000);
}

// Appendix A, "T_SNo with M0 File Writes (No Block Transfers)", Normal Mode.
TEST(RioTsnoTable, WithM0WritesNormalModeAllBaudRates) {
    for (RioBaud baud : {k57, k115, k230}) {
        expect_cell(TsnoTable::with_m0_writes, RioMode::normal, baud, 1, 8000, 6000, 4500);
        expect_cell(TsnoTable::with_m0_writes, RioMode::normal, baud, 2, 10000, 8000, 5500);
        expect_cell(TsnoTable::with_m0_writes, RioMode::normal, baud, 3, 12000, 10000, 7000);
        expect_cell(TsnoTable::with_m0_writes, RioMode::normal, baud, 4, 14000, 12000, 8000);
    }
}

// Appendix A, "T_SNo with M0 File Writes (No Block Transfers)", Complementary.
TEST(RioTsnoTable, WithM0WritesComplementaryMode) {
    const auto t = TsnoTable::with_m0_writes;
    const auto c = RioMode::complementary;
    expect_cell(t, c, k57, 1, 10000, 6000, 6000);
    expect_cell(t, c, k57, 2, 12000, 9000, 8000);
    expect_cell(t, c, k57, 3, 15000, 12000, 9000);
    expect_cell(t, c, k57, 4, 18000, 15000, 10000);
    expect_cell(t, c, k115, 1, 12000, 8000, 8000);
    expect_cell(t, c, k115, 2, 14000, 11000, 9000);
    expect_cell(t, c, k115, 3, 16000, 14000, 11000);
    expect_cell(t, c, k115, 4, 20000, 17000, 12000);
    expect_cell(t, c, k230, 1, 15000, 10000, 9000);
    expect_cell(t, c, k230, 2, 17000, 15000, 12000);
    expect_cell(t, c, k230, 3, 21000, 20000, 14000);
    expect_cell(t, c, k230, 4, 26000, 24000, 17000);
}

// Appendix A, "Determining T_SNo-bt" (page A-7): normal mode for all baud
// rates, complementary mode per baud rate.
TEST(RioTsnoBtTable, EveryCell) {
    const Micros normal[] = {16000, 19000, 22000, 25000};
    const Micros comp57[] = {19000, 23000, 26000, 28000};
    const Micros comp115[] = {24000, 27000, 30000, 34000};
    const Micros comp230[] = {32000, 36000, 39000, 42000};
    for (int racks = 1; racks <= 4; ++racks) {
        const auto i = static_cast<std::size_t>(racks - 1);
        for (RioBaud baud : {k57, k115, k230}) EXPECT_EQ(t_sno_bt(RioMode::normal, baud, racks), normal[i]);
        EXPECT_EQ(t_sno_bt(RioMode::complementary, k57, racks), comp57[i]);
        EXPECT_EQ(t_sno_bt(RioMode::complementary, k115, racks), comp115[i]);
        EXPECT_EQ(t_sno_bt(RioMode::complementary, k230, racks), comp230[i]);
    }
}

// The T_SNO tables have rows for 1 to 4 logical racks only.
TEST(RioTsnoTable, RejectsRackCountsOutsideOneToFour) {
    EXPECT_THROW(t_sno_cell(TsnoTable::without_m0_writes, RioMode::normal, k57, 0), std::invalid_argument);
    EXPECT_THROW(t_sno_cell(TsnoTable::without_m0_writes, RioMode::normal, k57, 5), std::invalid_argument);
    EXPECT_THROW(t_sno_cell(TsnoTable::with_block_transfers, RioMode::normal, k57, 1), std::invalid_argument);
    EXPECT_THROW(t_sno_bt(RioMode::normal, k57, 0), std::invalid_argument);
    EXPECT_THROW(t_sno_bt(RioMode::normal, k57, 5), std::invalid_argument);
}

// Appendix A, "Determining T_btX", T_ri table: 0.300 x length + 5.0 ms at
// 57.6K, 0.150 x length + 3.5 ms at 115.2K, 0.075 x length + 2.0 ms at 230.4K.
TEST(RioTriTable, FormulaPerBaudRate) {
    EXPECT_EQ(t_ri(k57, 1), 5300);
    EXPECT_EQ(t_ri(k57, 64), 24200);   // 0.300 x 64 + 5.0 = 24.2
    EXPECT_EQ(t_ri(k115, 8), 4700);    // worked example: 0.150(8) + 3.5 = 4.7 ms
    EXPECT_EQ(t_ri(k115, 2), 3800);    // worked example: 0.150(2) + 3.5 = 3.8 ms
    EXPECT_EQ(t_ri(k115, 64), 13100);  // worked example: 0.150(64) + 3.5 = 13.1 ms
    EXPECT_EQ(t_ri(k230, 10), 2750);   // 0.075 x 10 + 2.0 = 2.75
    EXPECT_EQ(t_ri(k230, 64), 6800);   // 0.075 x 64 + 2.0 = 6.8
    // A requested length of 0 lets the module send up to 64 words (chapter 5,
    // "Requested Word Count"), so it is charged as 64.
    EXPECT_EQ(t_ri(k115, 0), t_ri(k115, 64));
    EXPECT_THROW(t_ri(k115, 65), std::invalid_argument);
    EXPECT_THROW(t_ri(k115, -1), std::invalid_argument);
}

// Figures print as the manuals print them: 132.0 and 173.2 (appendix A
// examples), 2.75 (T_RIO table), 10.448 (section 4.5 by the formulas).
TEST(FormatMs, AtLeastOneDecimalAndNoTrailingZeros) {
    EXPECT_EQ(format_ms(132000), "132.0");
    EXPECT_EQ(format_ms(173200), "173.2");
    EXPECT_EQ(format_ms(2750), "2.75");
    EXPECT_EQ(format_ms(10448), "10.448");
    EXPECT_EQ(format_ms(0), "0.0");
    EXPECT_EQ(format_ms(18), "0.018");
    EXPECT_EQ(format_ms(-1500), "-1.5");
}

}  // namespace
}  // namespace softslc::throughput
