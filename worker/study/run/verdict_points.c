/* verdict_points: a sweep point read back from an image's name. */
#include "verdict_points.h"

#include <string.h>

size_t verdict_point_key_len(const char *image)
{
    const char *s = strrchr(image, '-');
    return s && s[1] == 's' && s[2] >= '0' && s[2] <= '9' ? (size_t)(s - image) : strlen(image);
}

long verdict_point_spp(const char *key, size_t len)
{
    long spp = 0;
    for (size_t i = 0; i + 5 <= len; i++)
        if (!strncmp(key + i, "-spp", 4) && key[i + 4] >= '1' && key[i + 4] <= '9') {
            size_t k = i + 4;
            long v = 0;
            while (k < len && key[k] >= '0' && key[k] <= '9' && v < 100000000)
                v = 10 * v + (key[k++] - '0');
            if (k == len || key[k] == '-')
                spp = v;
        }
    return spp;
}
