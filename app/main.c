#include <stdio.h>

#include "dembox.h"

int main(void)
{
    printf("dembox %s\n", DEM_VERSION);
    return 0;
}
