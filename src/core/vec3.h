/* A vector of three numbers, passed by value: the contact kernels are
 * called inside vectorised loops, where arrays would stop the compiler. */
#ifndef DEM_CORE_VEC3_H
#define DEM_CORE_VEC3_H

struct dem_vec3 {
    double x, y, z;
};

#endif
