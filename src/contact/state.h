/* Bits of a contact's state (one int per pair and per particle-wall
 * contact, carried with its history). */
#ifndef DEM_CONTACT_STATE_H
#define DEM_CONTACT_STATE_H

enum {
    DEM_CONTACT_ACTIVE = 1,  /* the contact was closed in the last step */
    DEM_CONTACT_SLIDING = 2, /* the contact slides (dynamic friction) */
    DEM_CONTACT_ROLLING = 4, /* the rolling resistance is at its limit */
    DEM_CONTACT_TWISTING = 8 /* the torsion resistance is at its limit */
};

/* Whether a contact slides at a positive Coulomb limit: its slip bit set,
 * friction (mu_s > 0) and, where a sliding contact carries mu_d f_C > 0,
 * a tangential force (c = n x f_t, its force record's). A contact at a
 * zero limit (no friction, or f_C = 0: a linear contact opening faster
 * than its dashpot allows, a Luding contact unloaded below its plastic
 * overlap) "slides" with no force at every step, as the force pass must
 * take it; the measurements do not count it. */
static inline int dem_contact_slides(int state, const double c[3], double mu_s,
                                     double mu_d)
{
    if (!(state & DEM_CONTACT_SLIDING) || !(mu_s > 0.0))
        return 0;
    return !(mu_d > 0.0) || c[0] != 0.0 || c[1] != 0.0 || c[2] != 0.0;
}

#endif
