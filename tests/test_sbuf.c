/* test_sbuf: the text buffer behind CSV, SVG and HTML: growth, escaping, base64 (RFC 4648), and
   the terminal sanitiser and per-format escapers on names with escapes and broken UTF-8. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "base/sbuf.h"

/* base64 of the first n bytes of s, as a fresh string. */
static char *b64(const char *s, size_t n)
{
    struct sbuf b = {0};
    sbuf_printf(&b, "%s", "");
    sbuf_base64(&b, (const uint8_t *)s, n);
    return sbuf_take(&b);
}

int main(void)
{
    /* RFC 4648 section 10 test vectors */
    static const char *const want[] = {"", "Zg==", "Zm8=", "Zm9v", "Zm9vYg==", "Zm9vYmE=", "Zm9vYmFy"};
    for (size_t n = 0; n <= 6; n++) {
        char *got = b64("foobar", n);
        CHECK(got && strcmp(got, want[n]) == 0);
        free(got);
    }
    char *hi = b64("\xff\xfe\x00", 3);
    CHECK(hi && strcmp(hi, "//4A") == 0);
    free(hi);

    struct sbuf b = {0};
    sbuf_escape(&b, "a<b & \"c\" 'd'>");
    char *s = sbuf_take(&b);
    CHECK(s && strcmp(s, "a&lt;b &amp; &quot;c&quot; &#39;d&#39;&gt;") == 0);
    free(s);
    CHECK(b.buf == NULL && b.len == 0); /* take resets */

    /* ESC, BEL, a C1 CSI (U+009B), a byte that is no UTF-8, a cut sequence; UTF-8 kept */
    const char *evil = "a\x1b[31mb\x07"
                       "c\xc2\x9b"
                       "d\xff"
                       "e\xe2\x82"
                       "f\xc3\xa9\n";
    const char *want_shown = "a\\x1b[31mb\\x07c\\xc2\\x9bd\\xffe\\xe2\\x82f\xc3\xa9\\n";
    char shown[128];
    CHECK(strcmp(sbuf_show(evil, shown, sizeof shown), want_shown) == 0);
    CHECK(strcmp(sbuf_show(evil, shown, 5), "a") == 0); /* cut before an escape that does not fit */
    sbuf_shown(&b, evil);
    s = sbuf_take(&b);
    CHECK(s && strcmp(s, want_shown) == 0);
    free(s);
    sbuf_escape(&b, "<\x1b\x01&\xfe>"); /* XML forbids the controls even as references */
    s = sbuf_take(&b);
    CHECK(s && strcmp(s, "&lt;\\x1b\\x01&amp;\\xfe&gt;") == 0);
    free(s);
    sbuf_csv(&b, "plain\x1b");
    sbuf_printf(&b, ",");
    sbuf_csv(&b, "a,\"b\"\n");
    s = sbuf_take(&b);
    CHECK(s && strcmp(s, "plain\x1b,\"a,\"\"b\"\"\n\"") == 0); /* lossless: read back as written */
    free(s);
    CHECK(sbuf_utf8_len("\xed\xa0\x80") == 0 &&
          sbuf_utf8_len("\xf0\x9f\x98\x80") == 4); /* a surrogate; U+1F600 */

    for (int i = 0; i < 1000; i++) /* grows past its first 256 bytes many times */
        sbuf_printf(&b, "%04d,", i);
    CHECK(b.len == 5000);
    CHECK(b.buf && strncmp(b.buf + 4995, "0999,", 5) == 0 && b.buf[5000] == 0);
    sbuf_free(&b);
    CHECK(sbuf_take(&b) == NULL); /* nothing written: NULL */
    return check_report("test_sbuf");
}
