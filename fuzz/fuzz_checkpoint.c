/* libFuzzer harness for the checkpoint reader: arbitrary bytes as
 * checkpoint.bin. A mutated file almost never keeps a valid CRC-32, which
 * would stop every input at the checksum; so, when the first byte is odd,
 * the file is read a second time with its last four bytes replaced by the
 * checksum of the others (as the writer stores it), and the reader's
 * checks of the header, the counts, the sections and every index are what
 * is exercised. Any crash, leak,
 * sanitizer report or message that is not one line is a finding; an
 * accepted file must give a simulation that can be freed.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "dembox.h"
#include "io/checkpoint.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void read_file(const char *path, const uint8_t *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return;
    if (size && fwrite(data, 1, size, f) != size) {
        fclose(f);
        return;
    }
    fclose(f);
    struct dem_sim s;
    struct dem_ckpt_run run;
    char *config = 0;
    struct dem_error err = {0, ""};
    memset(&run, 0, sizeof run);
    int rc = dem_checkpoint_read(path, &s, &config, &run, &err);
    if (rc != DEM_OK) {
        if (strchr(err.msg, '\n') || err.msg[0] == '\0')
            abort();
        return;
    }
    free(config);
    free(run.snap_t);
    dem_sim_destroy(&s);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[64];
    snprintf(path, sizeof path, "/tmp/dembox_fuzz_ckpt_%ld.bin", (long)getpid());
    read_file(path, data, size);
    if (size > 4 && (data[0] & 1)) {
        uint8_t *copy = malloc(size);
        if (copy) {
            memcpy(copy, data, size);
            uint32_t crc = dem_crc32(0, copy, size - 4);
            memcpy(copy + size - 4, &crc, 4);
            read_file(path, copy, size);
            free(copy);
        }
    }
    remove(path);
    return 0;
}
