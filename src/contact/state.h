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

#endif
