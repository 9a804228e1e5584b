#pragma once
// A program's locale as a German desktop's (std::locale::global(std::locale("de_DE.UTF-8"))
// gives it; this machine need not have that locale installed), for tests that what HFX writes
// and reads does not change with the locale.

#include <locale>
#include <string>

namespace hfx::test {

/// ',' for the decimal point, '.' between thousands.
struct GermanPunctuation : std::numpunct<char> {
    char do_decimal_point() const override { return ','; }
    char do_thousands_sep() const override { return '.'; }
    std::string do_grouping() const override { return "\3"; }
};

/// Makes the German punctuation the global C++ locale for its lifetime.
class GermanLocale {
public:
    GermanLocale() : before_(std::locale::global(std::locale(std::locale::classic(), new GermanPunctuation))) {}
    ~GermanLocale() { std::locale::global(before_); }
    GermanLocale(const GermanLocale&) = delete;
    GermanLocale& operator=(const GermanLocale&) = delete;

private:
    std::locale before_;
};

} // namespace hfx::test
