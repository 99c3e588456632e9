// Unit suffixes: conversion to SI and the dimension check against the parameter key.
#include <QtTest>

#include <cmath>
#include <numbers>

#include "core/io/units.hpp"
#include "core/params.hpp"

using namespace stickslip::io;

class TstUnits : public QObject {
    Q_OBJECT
private slots:
    void convertsToSI_data() {
        QTest::addColumn<QString>("key");
        QTest::addColumn<QString>("text");
        QTest::addColumn<double>("si");
        QTest::newRow("A plain SI") << "A" << "0.001" << 1e-3;
        QTest::newRow("A mm") << "A" << "0.4mm" << 0.4e-3;
        QTest::newRow("A um") << "A" << "20um" << 20e-6;
        QTest::newRow("A micro sign") << "A" << QString::fromUtf8("20\xC2\xB5m") << 20e-6;
        QTest::newRow("A greek mu") << "A" << QString::fromUtf8("20\xCE\xBCm") << 20e-6;
        QTest::newRow("A inch") << "A" << "0.5in" << 0.0127;
        QTest::newRow("A space") << "A" << "1.5 mm" << 1.5e-3;
        QTest::newRow("Dc um") << "Dc" << "20um" << 20e-6;
        QTest::newRow("tN N") << "tN" << "6.2N" << 6.2;
        QTest::newRow("tN mN") << "tN" << "500mN" << 0.5;
        QTest::newRow("tN lb") << "tN" << "1lb" << 0.45359237 * 9.80665;
        QTest::newRow("f Hz") << "f" << "3Hz" << 3.0;
        QTest::newRow("f kHz") << "f" << "0.2kHz" << 200.0;
        QTest::newRow("f 1/s") << "f" << "3/s" << 3.0;
        QTest::newRow("m kg") << "m" << "0.5kg" << 0.5;
        QTest::newRow("m g") << "m" << "530g" << 0.53;
        QTest::newRow("m lb as mass") << "m" << "1lb" << 0.45359237;
        QTest::newRow("eta s/m") << "eta" << "0.6s/m" << 0.6;
        QTest::newRow("eta s/mm") << "eta" << "0.6s/mm" << 600.0;
        QTest::newRow("vc m/s") << "vc" << "0.1m/s" << 0.1;
        QTest::newRow("vc mm/s") << "vc" << "100mm/s" << 0.1;
        QTest::newRow("k N/m") << "k" << "1e6N/m" << 1e6;
        QTest::newRow("k kN/m") << "k" << "8.446kN/m" << 8446.0;
        QTest::newRow("k N/mm") << "k" << "8.446N/mm" << 8446.0;
        QTest::newRow("epsT") << "epsT" << "1e6N/m" << 1e6;
        QTest::newRow("c Ns/m") << "c" << "0.669Ns/m" << 0.669;
        QTest::newRow("c N s/m") << "c" << "0.669 N s/m" << 0.669;
        QTest::newRow("c N*s/m") << "c" << "0.669N*s/m" << 0.669;
        QTest::newRow("c kg/s") << "c" << "0.669kg/s" << 0.669;
        QTest::newRow("dt us") << "dt" << "10us" << 1e-5;
        QTest::newRow("dt ms") << "dt" << "0.5ms" << 5e-4;
        QTest::newRow("phase deg") << "phase" << "90deg" << std::numbers::pi / 2;
        QTest::newRow("mu plain") << "mu" << "0.25" << 0.25;
        QTest::newRow("mu percent") << "mu" << "25%" << 0.25;
        QTest::newRow("plus sign") << "tN" << "+6.2N" << 6.2;
        QTest::newRow("negative") << "A" << "-1mm" << -1e-3;
    }
    void convertsToSI() {
        QFETCH(QString, key);
        QFETCH(QString, text);
        QFETCH(double, si);
        double v = 0;
        std::string err;
        QVERIFY2(parseParamValue(key.toStdString(), text.toStdString(), v, &err), err.c_str());
        QVERIFY2(std::abs(v - si) <= 1e-12 * std::abs(si), qPrintable(QString::number(v, 'g', 17)));
    }

    void rejectsWrongDimension_data() {
        QTest::addColumn<QString>("key");
        QTest::addColumn<QString>("text");
        QTest::addColumn<QString>("expectedUnit");
        QTest::newRow("A=3Hz") << "A" << "3Hz" << "[m]";
        QTest::newRow("f=3mm") << "f" << "3mm" << "[Hz]";
        QTest::newRow("k=6N") << "k" << "6N" << "[N/m]";
        QTest::newRow("tN=0.5kg") << "tN" << "0.5kg" << "[N]";
        QTest::newRow("eta=0.6m/s") << "eta" << "0.6m/s" << "[s/m]";
        QTest::newRow("vc=0.1s/m") << "vc" << "0.1s/m" << "[m/s]";
        QTest::newRow("mu=2N") << "mu" << "2N" << "(no unit)";
        QTest::newRow("m=2N") << "m" << "2N" << "[kg]";
        QTest::newRow("dt=1m") << "dt" << "1m" << "[s]";
        QTest::newRow("ms is not m*s") << "c" << "1ms" << "[N s/m]";
    }
    void rejectsWrongDimension() {
        QFETCH(QString, key);
        QFETCH(QString, text);
        QFETCH(QString, expectedUnit);
        double v = 42;
        std::string err;
        QVERIFY(!parseParamValue(key.toStdString(), text.toStdString(), v, &err));
        QCOMPARE(v, 42.0);
        // The message names key, value and expected unit.
        QVERIFY2(err.rfind(key.toStdString() + " = " + text.toStdString(), 0) == 0, err.c_str());
        QVERIFY2(err.find(expectedUnit.toStdString()) != std::string::npos, err.c_str());
    }

    void rejectsMalformed_data() {
        QTest::addColumn<QString>("text");
        QTest::newRow("empty") << "";
        QTest::newRow("no number") << "mm";
        QTest::newRow("unknown unit") << "3furlongs";
        QTest::newRow("nan") << "nan";
        QTest::newRow("inf") << "inf";
        QTest::newRow("two slashes") << "1m/s/s";
        QTest::newRow("junk") << "1m!";
        QTest::newRow("overflow") << "1e400";
    }
    void rejectsMalformed() {
        QFETCH(QString, text);
        double v = 0;
        std::string err;
        QVERIFY(!parseParamValue("A", text.toStdString(), v, &err));
        QVERIFY2(err.rfind("A = ", 0) == 0, err.c_str());
        QVERIFY(!err.empty());
    }

    void unknownKey() {
        double v = 0;
        std::string err;
        QVERIFY(!parseParamValue("nope", "1", v, &err));
        QVERIFY2(err.find("nope") != std::string::npos, err.c_str());
    }

    void everyParamKeyHasAUnit() {
        for (const std::string& key : stickslip::paramKeys()) {
            std::string unit;
            QVERIFY2(paramUnit(key, unit), key.c_str());
            Dimension d;
            QVERIFY(paramDimension(key, d));
            // The printed SI unit parses back to the key's dimension with factor 1.
            if (!unit.empty()) {
                Quantity q;
                std::string err;
                QVERIFY2(parseQuantity("1 " + unit, q, &err), err.c_str());
                QVERIFY2(q.dimension == d, key.c_str());
                QCOMPARE(q.valueSI, 1.0);
            }
        }
    }

    void quantityAndDimensionString() {
        Quantity q;
        std::string err;
        QVERIFY(parseQuantity("2 kN/m", q, &err));
        QVERIFY(q.hasUnit);
        QCOMPARE(q.valueSI, 2000.0);
        QCOMPARE(dimensionString(q.dimension), std::string("kg/s^2"));
        QVERIFY(parseQuantity("3", q, &err));
        QVERIFY(!q.hasUnit);
        QCOMPARE(dimensionString(Dimension{1, 0, -1}), std::string("m/s"));
        QCOMPARE(dimensionString(Dimension{0, 0, -1}), std::string("1/s"));
        QCOMPARE(dimensionString(Dimension{}), std::string("1"));
        QVERIFY(parseQuantity("1 m^2/s", q, &err));
        QCOMPARE(dimensionString(q.dimension), std::string("m^2/s"));
    }

    // Found by fuzz/fuzz_units: a huge exponent overflowed the int dimension (UB).
    void hugeExponentsAreRejected() {
        Quantity q;
        std::string err;
        QVERIFY(parseQuantity("1 m^9 s^-9", q, &err));
        QCOMPARE(q.dimension, (Dimension{9, 0, -9}));
        for (const char* text : {"1 mN00001857608177", "1 m^10", "1 s^-10", "1 m^2147483647", "1 kg^-2147483648"}) {
            err.clear();
            QVERIFY2(!parseQuantity(text, q, &err), text);
            QVERIFY2(err.find("exponent") != std::string::npos && err.find("-9 to 9") != std::string::npos, err.c_str());
        }
    }

    // Found by fuzz/fuzz_units (a 10 s timeout): splitting a long run of letters into unit atoms
    // tried every split (exponential); these returned only after minutes or never.
    void longLetterRunsSplitInLinearTime() {
        Quantity q;
        std::string err;
        QVERIFY(!parseQuantity("3 " + std::string(200, 'm') + "e", q, &err));
        QVERIFY2(err.find("unknown unit") != std::string::npos, err.c_str());
        QVERIFY(parseQuantity("3 " + std::string(60, 'm'), q, &err));  // mm·mm·…: (1e-3 m)^30
        QCOMPARE(q.dimension, (Dimension{30, 0, 0}));
        QVERIFY(parseQuantity("2 Nms", q, &err));  // N·ms, the longest head first
        QCOMPARE(q.dimension, (Dimension{1, 1, -1}));
        QCOMPARE(q.valueSI, 2e-3);
    }
};

QTEST_GUILESS_MAIN(TstUnits)
#include "tst_units.moc"
