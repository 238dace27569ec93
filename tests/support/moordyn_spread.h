// A MoorDyn input file shared by the importer's tests and its fuzz test.
#pragma once

namespace moorsim::testing {

// Three chain lines in 200 m of water (v2 layout), one of them two lines in series through
// a free point carrying a 5 t clump weight, written from the fairlead down.
inline constexpr const char* kMoorDynSpread =
    R"(--------------------- MoorDyn Input File -----------------------
A test spread
----------------------- LINE TYPES ------------------------------------------
TypeName   Diam    Mass/m     EA         BA/-zeta    EI   Cd     Ca     CdAx    CaAx
(name)     (m)     (kg/m)     (N)        (N-s/-)     (N-m^2)  (-)  (-)    (-)     (-)
chain      0.1     150        8.0e8      -0.6        0    2.0    0.9    0.3     0.0
wire       0.08    40         5.0e8      2.0e5       0    1.2    1.0    0.01    0.0
---------------------- POINTS --------------------------------
ID    Type      X       Y       Z       Mass   Volume  CdA    Ca
(#)   (-)       (m)     (m)     (m)     (kg)   (m^3)   (m^2)  (-)
1     Fixed     600     0       -200    0      0       0      0
2     Fixed     -300    520     -200    0      0       0      0
3     Fixed     -300    -520    -200    0      0       0      0
4     Vessel    10      0       -15     0      0       0      0
5     Vessel    -5      8.66    -15     0      0       0      0
6     Vessel    -5      -8.66   -15     0      0       0      0
7     Free      -150    -260    -190    5000   0.64    1.5    0.8
---------------------- LINES ----------------------------------------
ID   LineType   AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#)   (name)     (#)      (#)       (m)       (-)     (-)
1     chain      1        4         680       30      p
2     chain      2        5         680       30      p
3     wire       6        7         330       15      p
4     chain      7        3         350       15      p
---------------------- OPTIONS -----------------------------------------
0.001         dtM           time step
2.0e6         kBot          bottom stiffness (Pa/m)
2.0e5         cBot          bottom damping (Pa-s/m)
1020.0        WtrDnsty      water density (kg/m^3)
200           WtrDpth       water depth (m)
0.4           FrictionCoefficient
---------------------- OUTPUTS -----------------------------------------
FairTen1
END
------------------------- need this line --------------------------------------
)";

}  // namespace moorsim::testing
