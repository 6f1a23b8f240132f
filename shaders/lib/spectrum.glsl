// KHR_materials_dispersion (the dispersion axis, STRATA_DISPERSION): a path
// that reaches a dispersive dielectric draws one wavelength there and
// carries it to its end; paths that never reach one stay RGB.
//
// The wavelength lambda is drawn from pdf(lambda) over 360-830 nm; the
// path's throughput takes rgb(lambda) / pdf(lambda), where rgb(lambda) is
// the CIE 1931 matching functions in linear Rec. 709, each channel scaled
// so that a constant spectrum of 1 is (1, 1, 1): E[rgb / pdf] = 1, so the
// draw alone changes nothing where nothing disperses. From there on every
// colour (a BSDF's weight, a light's emission) is upsampled to its value at
// lambda, dot(colour, wavelengthBasis(lambda)), with basis functions that
// are positive and sum to 1: a colour in [0, 1] stays in [0, 1] and grey
// stays grey. Their round trip through rgb(lambda) is not the identity:
// (1, 0, 0) comes back as (1.147, 0.110, 0.012), (0, 1, 0) as (-0.135,
// 0.906, -0.018), (0, 0, 1) as (-0.013, -0.016, 1.007) (docs/gltf.md).
// Media after the draw (attenuation, scattering) stay RGB.
#ifndef STRATA_LIB_SPECTRUM_GLSL
#define STRATA_LIB_SPECTRUM_GLSL

const uint kDimWavelength = 0xfffffffau;  // the wavelength's pair (its first number)

// The path's wavelength in nm; 0: the path is RGB. Set once a path reaches
// a dispersive material (pathtrace.comp clears it at each path's start;
// wavefront.comp keeps it in PathState between stages).
float gWavelength = 0.0;

// One lobe of the matching functions' fit: a Gaussian with a width on each side.
float cieLobe(float lambda, float mu, float below, float above) {
    float t = (lambda - mu) / (lambda < mu ? below : above);
    return exp(-0.5 * t * t);
}

// CIE 1931 2-degree colour matching functions (x, y, z), the multi-lobe fit
// of Wyman, Sloan and Shirley 2013 (JCGT 2(2)).
vec3 cieXyz(float lambda) {
    float x = 1.056 * cieLobe(lambda, 599.8, 37.9, 31.0) + 0.362 * cieLobe(lambda, 442.0, 16.0, 26.7) -
              0.065 * cieLobe(lambda, 501.1, 20.4, 26.2);
    float y = 0.821 * cieLobe(lambda, 568.8, 46.9, 40.5) + 0.286 * cieLobe(lambda, 530.9, 16.3, 31.1);
    float z = 1.217 * cieLobe(lambda, 437.0, 11.8, 36.0) + 0.681 * cieLobe(lambda, 459.0, 26.0, 13.8);
    return vec3(x, y, z);
}

// The linear Rec. 709 colour of a unit of spectrum at lambda, per nm: XYZ to
// RGB, each channel divided by its integral over 360-830 nm (128.33516,
// 101.54379, 97.11689 for this fit), so a constant spectrum integrates to 1.
vec3 wavelengthRgb(float lambda) {
    vec3 c = cieXyz(lambda);
    vec3 rgb = vec3(dot(vec3(3.2404542, -1.5371385, -0.4985314), c),
                    dot(vec3(-0.9692660, 1.8760108, 0.0415560), c),
                    dot(vec3(0.0556434, -0.2040259, 1.0572252), c));
    return rgb * vec3(1.0 / 128.33516, 1.0 / 101.54379, 1.0 / 97.11689);
}

// Wavelengths drawn where the eye sees them: pdf proportional to
// 1 / cosh^2(0.0072 (lambda - 538)) over 360-830 nm (Radziszewski et al.
// 2009, as pbrt-v4 draws visible wavelengths), by inversion.
float sampleVisibleWavelength(float u) { return 538.0 - 138.888889 * atanh(0.85691062 - 1.82750197 * u); }

float visibleWavelengthPdf(float lambda) {
    if (lambda < 360.0 || lambda > 830.0) return 0.0;
    float c = cosh(0.0072 * (lambda - 538.0));
    return 0.0039398042 / (c * c);
}

// The basis a colour is upsampled with: the positive parts of
// wavelengthRgb, normalised to sum to 1.
vec3 wavelengthBasis(float lambda) {
    vec3 c = max(wavelengthRgb(lambda), vec3(0.0));
    float s = c.r + c.g + c.b;
    return s > 0.0 ? c / s : vec3(1.0 / 3.0);
}

// A colour along the path: its value at the path's wavelength once it has one.
vec3 pathSpectral(vec3 colour) {
    return gWavelength > 0.0 ? vec3(dot(colour, wavelengthBasis(gWavelength))) : colour;
}

// KHR_materials_dispersion's index at lambda (nm): Cauchy's two terms
// through n_d (the material's ior, at 587.56 nm) with the Abbe number
// V_d = 20 / dispersion, n = n_d + (n_d - 1) / V_d (523655 / lambda^2 -
// 1.5168), at least 1.
float dispersiveIor(float ior, float dispersion, float lambda) {
    float abbeInverse = dispersion / 20.0;
    return max(ior + (ior - 1.0) * abbeInverse * (523655.0 / (lambda * lambda) - 1.5168), 1.0);
}

#endif
