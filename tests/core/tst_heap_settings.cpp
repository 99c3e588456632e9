// applyHeapSettings (heap_settings.hpp): the defaults are accepted by glibc, a value mallopt
// cannot take is reported, and allocation still works after either.
#include <QtTest/QtTest>

#include <vector>

#include "core/heap_settings.hpp"

// AddressSanitizer's allocator replaces glibc's and its mallopt accepts nothing.
#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
#define GLIBC_MALLOC 1
#endif

using namespace stickslip;

class TestHeapSettings : public QObject {
    Q_OBJECT
private slots:
    void defaultsAreAccepted() {
#if defined(GLIBC_MALLOC)
        QVERIFY(applyHeapSettings());
#else
        applyHeapSettings();  // whatever it answers there, allocation must still work
#endif
        std::vector<double> big(1 << 22, 1.0);  // 32 MiB, at the mmap threshold
        QCOMPARE(big.back(), 1.0);
    }
    void refusedValueIsReported() {
        HeapSettings s;
        s.mmapThreshold_bytes = std::size_t{1} << 40;  // not an int
        QVERIFY(!applyHeapSettings(s));
        s.mmapThreshold_bytes = HeapSettings{}.mmapThreshold_bytes;
        s.trimThreshold_bytes = std::size_t{1} << 40;
        QVERIFY(!applyHeapSettings(s));
#if defined(GLIBC_MALLOC)
        QVERIFY(applyHeapSettings());  // back to the defaults
#endif
        std::vector<double> v(1000, 2.0);
        QCOMPARE(v.front(), 2.0);
    }
};

QTEST_APPLESS_MAIN(TestHeapSettings)
#include "tst_heap_settings.moc"
