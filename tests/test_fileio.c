/* test_fileio: bounded reads, atomic writes that leave nothing behind, and image files on disk. */
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "base/fileio.h"
#include "image/imgio.h"
#include "image/image.h"

static char dir[256];

/* out = dir + "/" + name. */
static void in_dir(char out[512], const char *name)
{
    snprintf(out, 512, "%s/%s", dir, name);
}

/* Number of entries in d, "." and ".." excluded; -1 if it cannot be opened. */
static int count_entries(const char *d)
{
    DIR *dh = opendir(d);
    if (!dh)
        return -1;
    int n = 0;
    for (struct dirent *de; (de = readdir(dh));)
        n += strcmp(de->d_name, ".") && strcmp(de->d_name, "..");
    closedir(dh);
    return n;
}

static int has(const struct err *e, const char *s)
{
    return strstr(e->msg, s) != NULL;
}

static void test_write_then_read(void)
{
    struct err e = {0};
    char path[512];
    in_dir(path, "a.bin");
    CHECK(fileio_write_atomic(path, "hello world", 11, &e) == 0);
    uint8_t *data;
    size_t len;
    CHECK(fileio_read_all(path, 100, &data, &len, &e) == 0);
    CHECK(len == 11 && !memcmp(data, "hello world", 11) && data[11] == '\0');
    free(data);
    struct stat st;
    CHECK(stat(path, &st) == 0 && (st.st_mode & 0777) == 0644);
    CHECK(count_entries(dir) == 1); /* no temporary file left */

    CHECK(fileio_write_atomic(path, "bye", 3, &e) == 0); /* replaces, shorter */
    CHECK(fileio_read_all(path, 3, &data, &len, &e) == 0 && len == 3 && !memcmp(data, "bye", 4));
    free(data);
    CHECK(fileio_read_all(path, 2, &data, &len, &e) == -1 && data == NULL);
    CHECK(has(&e, "file too large (3 bytes, limit 2)") && !strcmp(e.file, path));

    CHECK(fileio_write_atomic(path, "", 0, &e) == 0);
    CHECK(fileio_read_all(path, 0, &data, &len, &e) == 0 && len == 0 && data[0] == '\0');
    free(data);
    unlink(path);
}

static void test_read_errors(void)
{
    struct err e = {0};
    uint8_t *data = (uint8_t *)&e;
    size_t len = 5;
    char missing[512];
    in_dir(missing, "missing.png");
    CHECK(fileio_read_all(missing, 100, &data, &len, &e) == -1 && data == NULL && len == 0);
    CHECK(!strcmp(e.file, missing) && has(&e, "No such file or directory"));
    CHECK(fileio_read_all(dir, 100, &data, &len, &e) == -1 && has(&e, "Is a directory"));
    char fifo[512];
    in_dir(fifo, "fifo");
    CHECK(mkfifo(fifo, 0600) == 0);
    CHECK(fileio_read_all(fifo, 100, &data, &len, &e) == -1 && has(&e, "is a FIFO, not a regular file"));
    unlink(fifo);
}

/* fileio_kind names what a path is, through symbolic links too. */
static void test_kind(void)
{
    char fifo[512], link[512], dangling[512], file[512];
    in_dir(fifo, "kfifo");
    in_dir(link, "klink");
    in_dir(dangling, "kdangling");
    in_dir(file, "kfile");
    CHECK(mkfifo(fifo, 0600) == 0 && symlink(fifo, link) == 0 && symlink("nowhere", dangling) == 0);
    struct err e = {0};
    CHECK(fileio_write_atomic(file, "x", 1, &e) == 0);
    CHECK(fileio_kind(file) && !strcmp(fileio_kind(file), "a regular file"));
    CHECK(fileio_kind(fifo) && !strcmp(fileio_kind(fifo), "a FIFO"));
    CHECK(fileio_kind(link) && !strcmp(fileio_kind(link), "a symbolic link to a FIFO"));
    CHECK(fileio_kind(dangling) && !strcmp(fileio_kind(dangling), "a symbolic link to nothing"));
    CHECK(fileio_kind(dir) && !strcmp(fileio_kind(dir), "a directory"));
    CHECK(fileio_kind("/dev/null") && !strcmp(fileio_kind("/dev/null"), "a character device"));
    CHECK(fileio_kind(file) && fileio_kind("/no/such/file") == NULL);
    unlink(fifo);
    unlink(link);
    unlink(dangling);
    unlink(file);
}

static void test_write_errors(void)
{
    struct err e = {0};
    char path[512];
    snprintf(path, sizeof path, "%s/no/such/dir/x.png", dir);
    CHECK(fileio_write_atomic(path, "x", 1, &e) == -1);
    CHECK(has(&e, "cannot write") && has(&e, path) && has(&e, "No such file or directory"));
    CHECK(count_entries(dir) == 0); /* nothing created on the way */

    /* rename() over a directory fails after the data is written: the temporary must go */
    char sub[512];
    in_dir(sub, "taken");
    CHECK(mkdir(sub, 0755) == 0);
    CHECK(fileio_write_atomic(sub, "x", 1, &e) == -1 && has(&e, "cannot write"));
    CHECK(count_entries(dir) == 1);
    rmdir(sub);
    snprintf(path, sizeof path, "%s/", dir);
    CHECK(fileio_write_atomic(path, "x", 1, &e) == -1);

    /* a full disk, simulated by a file size limit: write() fails with EFBIG */
    char keep[512];
    in_dir(keep, "keep.bin");
    CHECK(fileio_write_atomic(keep, "old", 3, &e) == 0);
    struct rlimit old, tiny;
    void (*prev)(int) = signal(SIGXFSZ, SIG_IGN);
    CHECK(getrlimit(RLIMIT_FSIZE, &old) == 0);
    tiny = old;
    tiny.rlim_cur = 4096;
    CHECK(setrlimit(RLIMIT_FSIZE, &tiny) == 0);
    static char big[20000];
    int rc = fileio_write_atomic(keep, big, sizeof big, &e);
    CHECK(setrlimit(RLIMIT_FSIZE, &old) == 0);
    signal(SIGXFSZ, prev);
    CHECK(rc == -1 && has(&e, "File too large"));
    CHECK(count_entries(dir) == 1);
    uint8_t *data;
    size_t len;
    CHECK(fileio_read_all(keep, 100, &data, &len, &e) == 0 && len == 3 && !memcmp(data, "old", 3));
    free(data);
    unlink(keep);
}

static void test_images(void)
{
    struct rgb8 img, back;
    struct err e = {0};
    CHECK(image_alloc(&img, 5, 4, &e) == 0);
    for (int i = 0; i < 5 * 4 * 3; i++)
        img.px[i] = (uint8_t)(i * 13);
    char png[512];
    in_dir(png, "i.png");
    CHECK(imgio_write(png, &img, IMG_PNG, &e) == 0);
    CHECK(imgio_read(png, &back, &e) == 0);
    CHECK(back.w == 5 && back.h == 4 && !memcmp(back.px, img.px, 60));
    image_free(&back);
    char ppm[512];
    in_dir(ppm, "i.ppm");
    CHECK(imgio_write(ppm, &img, IMG_PPM, &e) == 0);
    CHECK(imgio_read(ppm, &back, &e) == 0);
    CHECK(back.w == 5 && back.h == 4 && !memcmp(back.px, img.px, 60));
    image_free(&back);
    unlink(png);
    unlink(ppm);

    char txt[512];
    in_dir(txt, "notes.txt");
    CHECK(fileio_write_atomic(txt, "hello", 5, &e) == 0);
    CHECK(imgio_read(txt, &back, &e) == -1 && back.px == NULL);
    CHECK(has(&e, "unknown image format (expected PNG or PPM)") && !strcmp(e.file, txt));
    CHECK(fileio_write_atomic(txt, "\x89PNG\r\n", 6, &e) == 0);
    CHECK(imgio_read(txt, &back, &e) == -1 && !strcmp(e.file, txt) && has(&e, "PNG"));
    CHECK(fileio_write_atomic(txt, "P5 1 1 255\n\x01", 12, &e) == 0);
    CHECK(imgio_read(txt, &back, &e) == -1 && has(&e, "P5"));
    unlink(txt);
    CHECK(imgio_read(txt, &back, &e) == -1 && has(&e, "No such file"));

    struct rgb8 empty = {0};
    CHECK(imgio_write(png, &empty, IMG_PNG, &e) == -1 && !strcmp(e.file, png));
    CHECK(count_entries(dir) == 0);
    image_free(&img);
}

/* The formats written, by name and by an output's extension (any case); none: 0; another: -1. */
static void test_formats(void)
{
    enum img_format f = IMG_PPM;
    CHECK(img_format_of_file("a.b.PNG", &f) == 1 && f == IMG_PNG);
    CHECK(img_format_of_file("a.Ppm", &f) == 1 && f == IMG_PPM);
    CHECK(img_format_of_file("render", &f) == 0);
    CHECK(img_format_of_file("a.EXR", &f) == 1 && f == IMG_EXR);
    CHECK(img_format_of_file("a.pfm", &f) == 1 && f == IMG_PFM);
    CHECK(img_format_of_file("a.hdr", &f) == -1 && img_format_of_file("a.tiff", &f) == -1);
    CHECK(img_format_of_file("a.png.x", &f) == -1 && img_format_of_file("a.", &f) == -1);
    CHECK(img_format_parse("ppm", &f) == 0 && f == IMG_PPM && !strcmp(img_format_name(f), "ppm"));
    CHECK(img_format_parse("png", &f) == 0 && f == IMG_PNG && !strcmp(img_format_name(f), "png"));
    CHECK(img_format_parse("PNG", &f) == -1 && img_format_parse("jpg", &f) == -1);
    char list[128];
    img_format_list(list, sizeof list);
    CHECK(!strcmp(list, "png, ppm, exr or pfm"));
    struct rgb8 img = {0};
    struct err e;
    CHECK(image_alloc(&img, 1, 1, &e) == 0);
    CHECK(imgio_write("/nonexistent/x.exr", &img, IMG_EXR, &e) == -1 && strstr(e.msg, "floats"));
    image_free(&img);
}

int main(void)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/test_fileio.XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    test_write_then_read();
    test_read_errors();
    test_kind();
    test_write_errors();
    test_images();
    test_formats();
    CHECK(rmdir(dir) == 0); /* every test cleans up after itself */
    return check_report("test_fileio");
}
