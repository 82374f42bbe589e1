/* test_sbuf: the text buffer behind CSV, SVG and HTML: growth, escaping, base64 (RFC 4648). */
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

    for (int i = 0; i < 1000; i++) /* grows past its first 256 bytes many times */
        sbuf_printf(&b, "%04d,", i);
    CHECK(b.len == 5000);
    CHECK(b.buf && strncmp(b.buf + 4995, "0999,", 5) == 0 && b.buf[5000] == 0);
    sbuf_free(&b);
    CHECK(sbuf_take(&b) == NULL); /* nothing written: NULL */
    return check_report("test_sbuf");
}
