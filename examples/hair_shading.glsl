// hair_shading.glsl: the hair's fragment shader and its self-shadowing,
// one text for examples/gl_marschner.c (GL 3.3 core, read at run time)
// and the web page examples/web/hairfur_web.c (WebGL2, GLSL ES 3.00,
// built in by make web). It has no #version line: each program puts its
// prelude first, "#version 330 core" or "#version 300 es" with the
// precisions (highp float, int, sampler2D).
//
// With HAIR_SHADING_SHADOW_ONLY defined before it, only the
// self-shadowing (hair_trans, hair_shadow) is compiled, for the skin's
// fragment shader: the program declares its own inputs and main().
//
// The hair: the energy-conserving Marschner fibre from its two LUTs
// (hf_lut_bake_m / _n with HF_LUT_ENERGY, baked without absorption;
// docs/luts.md), with the hair colour as an absorption per channel, and
// Zinke et al.'s dual scattering from the tables of hf_lut_bake_dual
// (u_dual; 0: single scattering of the light that arrives unscattered
// only); or Kajiya-Kay with its diffuse term; ambient; self-shadowing.
// Lighting is done in linear space and written with gamma 2.2.
//
// Self-shadowing, shared by the hair and the body. u_shadow holds the
// depth (from the light) of the nearest hair or skin, z0.
// Deep opacity maps (u_deep; Yuksel and Keyser 2008): u_opacity's R, G,
// B hold the opacity of the hair in three layers behind z0, ending
// u_layers metres past it (the last takes everything further), and its
// A the depth of the nearest skin. The hair's opacity in front of a
// point is the layers' sum up to its depth, linear within a layer; the
// light arriving unscattered is exp(-u_opacity_k * opacity), times the
// body's own falloff exp(-u_shadow_k d) where the point is d behind the
// skin. u_deep 0: one depth map read as an approximate deep shadow map,
// light falling off exponentially with the depth behind z0, u_shadow_k
// per metre (set from the hair length).
// hair_trans is the light that arrives unscattered, exp(-n) with n the
// fibres crossed on average; hair_shadow holds it at 12 % at the least
// (light that got through scattered, where dual scattering does not say
// how much). 3 x 3 taps soften the edges (2 x 2 of the deep maps, whose
// layers are smooth already: the read costs less).

// ---- the hair's inputs and settings ----
#ifndef HAIR_SHADING_SHADOW_ONLY
in vec3 v_position, v_tangent, v_texcoord;
in vec4 v_color;
in vec2 v_c3d;
uniform sampler2D u_lut_m, u_lut_n, u_ramp;
uniform sampler2D u_dual0, u_dual2; // hf_lut_bake_dual planes 0, 2
uniform int u_kajiya, u_color3d;
uniform float u_spec;            // 0 = diffuse + ambient only
uniform float u_dual;            // 1 = dual scattering
uniform float u_dither;          // alpha dither (alpha to coverage)
uniform vec3 u_eye, u_light_dir, u_light_color, u_ambient;
uniform float u_oit;             // 1: weighted blended OIT
uniform float u_oit_ref, u_oit_scale; // its depth weight (metres)
#endif

// ---- self-shadowing (the hair and the body) ----
uniform sampler2D u_shadow, u_opacity;
uniform mat4 u_light_view_proj;
uniform float u_shadow_on, u_shadow_k, u_shadow_depth, u_shadow_bias;
uniform float u_deep, u_opacity_k;
uniform vec3 u_layers;
// the deep opacity maps' transmittance at d metres past z0
float deep_trans(vec2 t, float d, float z) {
    vec4 o = texture(u_opacity, t);
    vec3 lo = vec3(0.0, u_layers.xy), w = u_layers - lo;
    float a = dot(o.rgb, clamp((vec3(d) - lo) / w, 0.0, 1.0));
    float b = (z - o.a) * u_shadow_depth - u_shadow_bias;
    return exp(-u_opacity_k * a - u_shadow_k * max(b, 0.0));
}
float hair_trans(vec3 p) {
    if (u_shadow_on == 0.0) return 1.0;
    vec4 q = u_light_view_proj * vec4(p, 1.0);
    vec3 s = q.xyz / q.w * 0.5 + 0.5;
    if (any(lessThan(s, vec3(0.0))) || any(greaterThan(s, vec3(1.0))))
        return 1.0;
    // taps: 3 x 3, 1.5 texels apart (single); 2 x 2, 2 apart (deep)
    int n = u_deep != 0.0 ? 2 : 3;
    vec2 texel = (u_deep != 0.0 ? 2.0 : 1.5)
                 / vec2(textureSize(u_shadow, 0));
    vec2 o0 = vec2(u_deep != 0.0 ? -0.5 : -1.0);
    float sum = 0.0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            vec2 t = s.xy + (o0 + vec2(x, y)) * texel;
            float z0 = texture(u_shadow, t).r;
            float d = (s.z - z0) * u_shadow_depth - u_shadow_bias;
            sum += u_deep != 0.0 ? deep_trans(t, d, s.z)
                                 : exp(-u_shadow_k * max(d, 0.0));
        }
    return sum / float(n * n);
}
float hair_shadow(vec3 p) { return mix(0.12, 1.0, hair_trans(p)); }

// ---- the hair: root fade, Marschner, dual scattering, OIT ----
#ifndef HAIR_SHADING_SHADOW_ONLY
in float v_root;
uniform float u_root_fade; // metres; 0: none
float root_fade() {
    return u_root_fade > 0.0 ? smoothstep(0.0, u_root_fade, v_root)
                             : 1.0;
}
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_weight; // OIT: the weights' sum
const float PI = 3.14159265;
const float cosMin = 1e-2;       // grazing theta_r guard
const float d_f = 0.7, d_b = 0.7; // Zinke's density factors
// a unit-area Gaussian of theta_h (x = theta_h - shift)
float g1(float x, float var) {
    return exp(-0.5 * x * x / var) * inversesqrt(2.0 * PI * var);
}
void main() {
    vec3 T = normalize(v_tangent);
    vec3 L = u_light_dir;
    vec3 V = normalize(u_eye - v_position);
    vec3 srgb = u_color3d != 0 ? texture(u_ramp, v_c3d).rgb : v_color.rgb;
    // per-strand brightness variation from a hash of the root UV (the
    // same for every fragment of a strand): strands read as strands
    float h = fract(sin(dot(v_texcoord.xy, vec2(12.9898, 78.233))) * 43758.5453);
    vec3 base = pow(srgb, vec3(2.2)) * (0.7 + 0.6 * h);
    float TL = dot(T, L), TV = dot(T, V);
    float sinTL = sqrt(max(0.0, 1.0 - TL * TL));   // cos(theta_i)
    float sinTV = sqrt(max(0.0, 1.0 - TV * TV));   // cos(theta_r)
    float fd = hair_trans(v_position); // light arriving unscattered
    float shadow = mix(0.12, 1.0, fd); // hair_shadow, read once
    vec3 lit;
    if (u_kajiya != 0) {
        // Kajiya-Kay: mirror cone, V pointing away (spec section 10)
        float c = max(0.0, sinTL * sinTV - TL * TV);
        vec3 spec = vec3(0.35 * pow(c, 80.0)) + 0.25 * base / max(base.r, 1e-3)
                    * pow(c, 12.0);
        lit = shadow * (0.8 * base * sinTL + u_spec * spec);
    } else if (u_spec == 0.0) {
        lit = shadow * 0.8 * base * sinTL;
    } else {
        vec4 M = texture(u_lut_m, vec2(TL, TV) * 0.5 + 0.5); // M_R, M_TT, M_TRT, M_p>=3
        vec3 Lp = L - TL * T, Vp = V - TV * T;
        float cosPhi = dot(Lp, Vp) * inversesqrt(max(dot(Lp, Lp) * dot(Vp, Vp), 1e-12));
        vec4 N = texture(u_lut_n, vec2(sinTL, cosPhi) * 0.5 + 0.5); // N_R .. N_p>=3
        // the hair colour as absorption per fibre radius (Chiang et al.
        // 2016, no azimuthal roughness): what multiple scattering turns
        // into that colour; a pass through the fibre is about 1.86
        // radii / cos(theta_t) long
        vec3 sigma = pow(log(clamp(base, 1e-3, 0.999)) / 5.969, vec3(2.0));
        vec3 Tr = exp(-sigma * 1.86 / sqrt(1.0 - TL * TL / (1.55 * 1.55)));
        float invCos = 1.0 / max(sinTV, cosMin);
        // S = sum_p M_p N_p / cos(theta_r); p = 1, 2, 3.. cross it p times
        vec3 single = (M.r * N.r + (M.g * N.g + (M.b * N.b + M.a * N.a * Tr) * Tr) * Tr) * invCos;
        vec3 S = fd * single;
        if (u_dual != 0.0) {
            // Zinke et al. 2008 from the tables at (sigma / (1 + sigma),
            // cos(theta_i)): the amounts per channel, the lobes' shifts
            // and widths at the mean absorption (per channel they part
            // into colour fringes); Zinke's Gaussians of theta_h halved,
            // as this fibre's M is per unit of theta_r
            vec3 u = sigma / (1.0 + sigma);
            float sm = dot(sigma, vec3(0.2126, 0.7152, 0.0722));
            vec2 um = vec2(sm / (1.0 + sm), sinTL);
            vec4 f = texture(u_dual0, um);  // a_f, alpha_f, beta_f
            vec4 m = texture(u_dual2, um);  // A_b, delta_b, sigma_b
            vec3 af = vec3(texture(u_dual0, vec2(u.r, sinTL)).x,
                           texture(u_dual0, vec2(u.g, sinTL)).x,
                           texture(u_dual0, vec2(u.b, sinTL)).x);
            vec3 Ab = vec3(texture(u_dual2, vec2(u.r, sinTL)).x,
                           texture(u_dual2, vec2(u.g, sinTL)).x,
                           texture(u_dual2, vec2(u.b, sinTL)).x);
            // fibres crossed on the way in: the shadow map's exp(-n)
            float n = -log(max(fd, 1e-4));
            vec3 Tf = pow(af, vec3(n));   // light that got here forward
            float vf = n * f.z * f.z;     // its spread, variance in theta_h
            float thH = 0.5 * (asin(clamp(TL, -1.0, 1.0)) + asin(clamp(TV, -1.0, 1.0)));
            float inv = 1.0 / (PI * max(sinTV * sinTV, cosMin));
            float gD = g1(thH - m.y, m.z * m.z) * inv;      // f_back / A_b
            float gS = g1(thH - m.y, m.z * m.z + vf) * inv; // spread
            // single scattering of the forward-scattered light: N_G =
            // a_f / pi, one lobe of the forward average shift, width
            float gF = 0.5 * g1(thH - f.y, f.z * f.z + vf) * inv;
            S = fd * (single + d_b * Ab * gD)
                + max(Tf - fd, 0.0) * d_f * (af * gF + PI * d_b * Ab * gS);
        }
        lit = 3.0 * S * sinTL;     // cos(theta_i); 3: artistic gain
    }
    // a cheap ambient occlusion that darkens hair near its root: inner
    // hair gets less
    float occ = mix(0.35, 1.0, smoothstep(0.0, 0.3, v_texcoord.z));
    vec3 c = u_ambient * base * occ + u_light_color * occ * lit;
    // dither the alpha per pixel: alpha to coverage alone quantises
    // the tip fade to 4 levels, which shows as concentric shells
    float n = fract(52.9829189 * fract(dot(gl_FragCoord.xy,
                                           vec2(0.06711056, 0.00583715))));
    float alpha = clamp(v_color.a * root_fade() + u_dither * (n - 0.5),
                        0.0, 1.0);
    o_color = vec4(pow(c, vec3(1.0 / 2.2)), alpha);
    o_weight = vec4(0.0);
    if (u_oit != 0.0) {
        // McGuire and Bavoil 2013: the colour premultiplied and
        // weighted, nearer fragments weighing more (e times per
        // u_oit_scale metres); alpha multiplies the revealage
        float d = length(u_eye - v_position);
        float wt = alpha * clamp(exp((u_oit_ref - d) / u_oit_scale),
                                 1e-6, 1e6);
        o_color = vec4(o_color.rgb * wt, alpha);
        o_weight = vec4(wt, 0.0, 0.0, 0.0);
    }
}
#endif
