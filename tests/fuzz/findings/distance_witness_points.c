/* SPDX-License-Identifier: MIT */
/* Finding: kairos_distance returns closest points that do not match the distance when one shape is
 * about 1e10 times larger than the other (moderate magnitudes, well inside KAIROS_MAX_MAGNITUDE).
 * 1. A unit sphere against a large triangle grown by a unit sphere (hull of 3 points + sphere(1)):
 *    distance 2.18 (right: the bare triangle is 3.18 away) but point_b is (3.7e10, 2.4e10, -4.9),
 *    4.4e10 from point_a (termination NO_PROGRESS). Without the Minkowski sum the points are right.
 * 2. A needle hull (60 points, 1.8e14 long and 2e5 thick) against a unit sphere at its origin:
 *    distance 968 but |point_b - point_a| = 2.2e12 (termination JOHNSON_FAILED), and the other order
 *    answers 3143.
 * The raw input fuzz_queries-distance_witness_points.bin is the same at unit scale: a point against
 * an identity-transformed needle hull (56 points, 1.9 long, 2e-9 thick) gives distance 3.3e-10 but
 * points 0.40 apart (termination JOHNSON_FAILED). Exits 1 while either case here is present.
 * Build: see README.md. */
#include <math.h>
#include <stdio.h>
#include <kairos/kairos.h>

static const kairos_vec3 needle_hull[60] = {
    {-52111452893940.898, 25848.082818684717, -87734.428861386696},
    {-30202135171196.121, 78447.215663046925, -81149.347633945872},
    {71658102823802.891, -97069.007126982353, -60395.706855037264},
    {-70631518241406.828, 32632.176300185536, 99246.350043987855},
    {69899521267964.391, 60924.409214204861, 64073.256106413792},
    {25635749407079.512, -91623.692020276227, 42311.887232166169},
    {-67306144112719.18, -16648.964283451929, 56862.778326403546},
    {-24781367353696.316, -79185.300245580293, -75857.655778543354},
    {42136543320440.992, 50382.754342450651, 70594.744547671056},
    {79993993508697.516, -47403.376960027694, 33617.443771788348},
    {55838093455117.719, -75472.187518443068, -78722.642530617071},
    {42101725335362.336, -54236.280239644228, -93042.425831405286},
    {-97219945457840.078, 77381.91950120416, -45927.368544837213},
    {-88374609955558.906, 76612.67395781404, 71210.953537241294},
    {-7577865982924.625, -39923.729321188352, 60417.679249908979},
    {15638012712385.252, 59000.407366792911, -97986.057558416054},
    {-81192468085719.828, 62626.897565211271, 56435.61200522985},
    {-38556660505334.75, 96161.400837110603, -32221.84932996659},
    {58988550543803.5, -81337.679892422224, -69140.189538334511},
    {70132459959092.789, 31018.699449420998, 68374.11464240613},
    {29009681492829.852, -29879.383876515811, -42286.234156408427},
    {73479420152715.516, 25282.561236076595, -79267.306562433936},
    {-97298531367240.531, 13834.651299693523, -27702.161626971258},
    {77445983055748.609, 17411.156789786754, -49650.762768892018},
    {-44889596705784.188, -26065.257202389945, -38815.223597228382},
    {61523772482809.961, -81573.686863998999, -92552.19359166197},
    {-76878779426289.297, 29389.293702464616, -29523.189279022623},
    {22056520012370.863, -34525.907748766142, 51425.956256026577},
    {-64384657665151.156, 11900.739795313964, -87314.046872903069},
    {18644903946531.801, 85112.697645004402, -61158.315531212189},
    {-19560148486994.145, 83013.088846863378, -77420.733741691423},
    {90141015248920.906, -83121.326005276554, -76579.88651534509},
    {-38385125180538.312, 38102.114361511391, 76971.872030936735},
    {33088829126957.699, -89017.81783866683, -22725.439999373153},
    {60630831627558.648, -9693.8360405592448, -26939.790551306312},
    {67292810471463.008, 15637.232108689748, -46022.201640117702},
    {32745495523236.223, 67028.333583436703, 33475.703298279223},
    {16000902700481.867, -87779.324604230336, -1570.1177263147904},
    {-8747695963645.4414, 74961.270101392874, -26987.924936173993},
    {-79176384363227.188, -52001.69096704985, 12086.187730451182},
    {-52846434199905.648, -53272.341091558854, 64210.500796087639},
    {-30642864256193.359, 32451.916554265961, -61196.13012338501},
    {-75621893643719.453, -67486.906609033496, -95594.87273930198},
    {-79773584493180.609, 99307.091046910471, -81619.196926367527},
    {87783193710311.406, -1041.4323055198961, 4524.9525161486845},
    {40480665423673.125, 52598.438188137967, -76464.286703307036},
    {59569133436556.008, -62776.054225940556, -23409.925850739844},
    {-59473439980330.078, -22704.368349144002, -13209.453622052302},
    {-56074106699726.719, 39095.419174112481, 90224.025049820732},
    {-82457733347142.719, 89371.283460302482, 60135.904416885765},
    {-93992041670365.406, 96430.957702442858, -44400.242058297736},
    {-93428275813783.219, -68836.547545710244, -35876.304865343016},
    {-51393487670945.047, -66582.544126879497, 59647.763458806963},
    {74659651677518.641, -79986.995813864705, -8937.7857331913729},
    {24432689417604.793, -82797.230884784614, 87183.712541157511},
    {78447068450844.75, -92327.687337827214, 12745.119910202973},
    {-23197015404908.883, -37974.54280598092, -94299.325353268359},
    {59547754555227.875, -39566.676835232385, -63277.634745798219},
    {43233155995607.664, -33021.810974814449, -21996.368815959879},
    {40944985759742.125, 65014.1725707226, 76810.735935741599},
};
static int check(const char* what, const kairos_shape* a, const kairos_shape* b) {
    const kairos_pose pose = {{-4, -4, -4}, {0, 0, 0, 1}};
    kairos_distance_result r;
    const int32_t s = kairos_distance(a, &pose, b, &pose, NULL, &r);
    if (s != KAIROS_OK) {
        printf("%s: %s\n", what, kairos_status_name(s));
        return 0;
    }
    const double dx = r.point_b.x - r.point_a.x, dy = r.point_b.y - r.point_a.y, dz = r.point_b.z - r.point_a.z;
    const double between = sqrt(dx * dx + dy * dy + dz * dz);
    printf("%s: distance %.17g (termination %d), |point_b - point_a| %.17g\n  point_a (%.17g %.17g %.17g)\n"
           "  point_b (%.17g %.17g %.17g)\n",
           what, r.distance, r.termination, between, r.point_a.x, r.point_a.y, r.point_a.z, r.point_b.x, r.point_b.y,
           r.point_b.z);
    if (fabs(between - r.distance) > 1e-6 * (1 + r.distance)) {
        printf("BUG: the closest points are not the distance apart\n");
        return 1;
    }
    return 0;
}

int main(void) {
    static const kairos_vec3 corners[3] = {
        {67551594266.012558, 43071141640.43, 0}, {-3489279232.7082758, -72054444154.304169, 0}, {-4, -4, -4}};
    kairos_shape *ball = NULL, *triangle = NULL, *rounded = NULL, *needle = NULL;
    if (kairos_shape_sphere(1, &ball) != KAIROS_OK || kairos_shape_convex_hull(corners, 3, &triangle) != KAIROS_OK ||
        kairos_shape_minkowski_sum(triangle, ball, &rounded) != KAIROS_OK ||
        kairos_shape_convex_hull(needle_hull, sizeof needle_hull / sizeof needle_hull[0], &needle) != KAIROS_OK) {
        printf("setup failed: %s\n", kairos_last_error());
        return 2;
    }
    int bugs = 0;
    bugs += check("sphere(1) vs triangle", ball, triangle);
    bugs += check("sphere(1) vs triangle + sphere(1)", ball, rounded);
    bugs += check("needle vs sphere(1)", needle, ball);
    bugs += check("sphere(1) vs needle", ball, needle);
    kairos_shape_release(ball);
    kairos_shape_release(triangle);
    kairos_shape_release(rounded);
    kairos_shape_release(needle);
    return bugs > 0 ? 1 : 0;
}
