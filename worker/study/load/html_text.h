/* html_text: a run of HTML or SVG around one escaped name, the study's pages' commonest step. */
#ifndef HTML_TEXT_H
#define HTML_TEXT_H

#include "base/sbuf.h"

/* before as it is, text escaped (sbuf_escape), then after as it is (neither a format). */
static inline void html_text(struct sbuf *b, const char *before, const char *text, const char *after)
{
    sbuf_printf(b, "%s", before);
    sbuf_escape(b, text);
    sbuf_printf(b, "%s", after);
}

#endif
