//! `sin θ` and `cos θ` exactly as glibc computes them, without the library call.
//!
//! Gymnasium's CartPole calls Python's `math.sin` and `math.cos`, which on Linux are glibc's
//! libm. To give the same states bit for bit, the native CartPole must get the same sines
//! and cosines. Calling libm does that but is slow for CartPole's inner loop: a call per
//! angle, and glibc's `sincos` saves and checks the MXCSR rounding mode on every call
//! (half the time spent in it, by `perf`).
//!
//! For `2^-27 <= |x| < 0.855469` (every angle a CartPole episode reaches: it terminates at
//! 0.2095 rad) this module repeats glibc's own computation: the IBM Accurate Mathematical
//! Library's `do_sin`/`do_cos` (`sysdeps/ieee754/dbl-64/s_sin.c`, glibc 2.28 and later), a
//! degree-9 Taylor polynomial for `sin` below 0.126 and otherwise a 1/128-spaced table of
//! `sin`/`cos` in double-double with short polynomial corrections. The operations are
//! the same, in the same order, and the multiply-adds are fused exactly where GCC fused
//! them in glibc's x86-64 FMA build (`__sin_fma`, `__cos_fma`, `__sincos_fma`, which glibc
//! selects on CPUs with FMA and AVX2), read off its machine code. Fused multiply-adds are
//! exactly rounded, so the same operations give the same bits.
//!
//! The inline path is used only where it must agree with the platform's libm: Linux with
//! glibc, an x86-64 CPU with FMA and AVX2, and a self-check at first use that compares it
//! with libm's `sin` and `cos` on 4,096 angles (see [`backend`]). Anywhere else, for
//! angles outside the range, or with `PPO_TUTOR_LIBM_SINCOS` set, [`sin_cos`] calls libm.
//! `tests/sincos.rs` compares the two on ten million more angles.
//!
//! `pulp` compiles the kernel for the CPU found at run time, so each `mul_add` is one FMA
//! instruction. [`dispatch`] runs whole pieces of work in that compiled code, generic over
//! the [`Math`] in use: `CartPole::step` is one, and the vector env's physics another
//! (its loops vectorise there). [`Math`] also divides: `Inline` with the proven fast
//! division of [`super::quotient`], which needs FMA to be fast.
//!
//! The 440-entry table below holds glibc's `__sincostab` values (`sin(i/128)` and
//! `cos(i/128)` as high and low parts, i = 0..109), bit for bit: a fresh computation in
//! high precision differs in the last bit of 17 low parts, and bit-for-bit results need
//! glibc's own.

use super::quotient::Divisor;
use super::seeding::NumpyRng;

/// `1.5 * 2^45`: adding it to `|x|` rounds `|x|` to a multiple of 1/128 and leaves the
/// multiple's index in the low bits.
const BIG: f64 = f64::from_bits(0x42c8_0000_0000_0000);
/// Below this `|x|`, `sin` uses the Taylor polynomial instead of the table.
const TAYLOR_LIMIT: f64 = f64::from_bits(0x3fc0_20c4_9ba5_e354); // 0.126
// Taylor coefficients for sin (−1/3!, 1/5!, −1/7!, 1/9!, −1/11!, as glibc rounds them).
const S1: f64 = f64::from_bits(0xbfc5_5555_5555_5555);
const S2: f64 = f64::from_bits(0x3f81_1111_1111_0ece);
const S3: f64 = f64::from_bits(0xbf2a_01a0_19db_08b8);
const S4: f64 = f64::from_bits(0x3ec7_1de2_7b9a_7ed9);
const S5: f64 = f64::from_bits(0xbe5a_ddff_c2fc_df59);
// The table path's short corrections.
const SN3: f64 = f64::from_bits(0xbfc5_5555_5555_5515);
const SN5: f64 = f64::from_bits(0x3f81_1110_e829_872f);
const CS2: f64 = f64::from_bits(0x3fe0_0000_0000_0000);
const CS4: f64 = f64::from_bits(0xbfa5_5555_5555_5535);
const CS6: f64 = f64::from_bits(0x3f56_c16b_edd9_e239);

/// The high word of `|x|` below which glibc returns `sin x = x`, `cos x = 1` (`2^-27`).
const TINY_HIGH_WORD: u32 = 0x3e40_0000;
/// The high word of `|x|` from which glibc leaves the table range (`0.855469`).
const RANGE_HIGH_WORD: u32 = 0x3feb_6000;

/// glibc's `__sincostab`, then zeros up to 512 entries so that a masked index needs no
/// bounds check (which keeps the vector loop branch-free).
#[rustfmt::skip]
static TABLE: [u64; 512] = {
    let glibc: [u64; 440] = [
    0x0000000000000000, 0x0000000000000000, 0x3ff0000000000000, 0x0000000000000000,
    0x3f7fffeaaaaeeeef, 0xbc1e45e2ec67b77c, 0x3fefffc000155552, 0x3c8f4a01a0196dae,
    0x3f8fffaaaaeeeed5, 0xbc02ab639a9f0777, 0x3fefff000155549f, 0x3c828a28a03a5ef3,
    0x3f97ff7001033255, 0x3bfefe2b51527336, 0x3feffdc006bff7e6, 0x3c8ae6dae86977bd,
    0x3f9ffeaaaeeee86f, 0xbc3cd406fb224ae2, 0x3feffc00155527d3, 0xbc83b54492d89b5b,
    0x3fa3feb2b12d45d5, 0x3c34ec54203d1c11, 0x3feff9c03414a7ba, 0x3c6991f4be6c59bf,
    0x3fa7fdc01032fba9, 0xbc4599bdf46e997a, 0x3feff7006bfdf99f, 0xbc78b3b560648d5f,
    0x3fabfc6d78586dac, 0x3c18e4fd03dbf236, 0x3feff3c0c8103a31, 0x3c74856dbddc0e66,
    0x3faffaaaeeed4edb, 0xbc42d16d32684b69, 0x3feff0015549f4d3, 0x3c8328387b99426f,
    0x3fb1fc343d808bef, 0xbc5f3d32e6f3be4f, 0x3fefebc222a8ef9f, 0x3c57934934f54c77,
    0x3fb3facb12d1755b, 0xbc5921915299468c, 0x3fefe7034129ef6f, 0xbc6cbf4337c96f97,
    0x3fb5f911fd10b737, 0xbc50184f02be9102, 0x3fefe1c4c3c873eb, 0xbc35a9c9057c4a02,
    0x3fb7f701032550e4, 0x3c3afc2d1800501a, 0x3fefdc06bf7e6b9b, 0x3c831902b535f8db,
    0x3fb9f4902d55d1f9, 0x3c52696d7eac1dc1, 0x3fefd5c94b43e000, 0xbc62e768cb4f92f9,
    0x3fbbf1b78568391d, 0x3c5e91841dea4cc8, 0x3fefcf0c800e99b1, 0x3c6ea3d786d186ac,
    0x3fbdee6f16c1cce6, 0xbc450f8e2fb71673, 0x3fefc7d078d1bc88, 0x3c8075d2447db685,
    0x3fbfeaaeee86ee36, 0xbc4afcb2bcc6f03b, 0x3fefc015527d5bd3, 0x3c8b68f35094efb8,
    0x3fc0f3378ddd71d1, 0x3c6d8468724f0f9e, 0x3fefb7db2bfe0695, 0x3c821dadf4f65ab1,
    0x3fc1f0d3d7afceaf, 0xbc66ef95099769a5, 0x3fefaf22263c4bd3, 0xbc552ace133a2769,
    0x3fc2ee285e4ab88f, 0xbc6e4d0f05dee058, 0x3fefa5ea641c36f2, 0x3c404da6ed17cc7c,
    0x3fc3eb312c5d66cb, 0x3c647d666b66cb91, 0x3fef9c340a7cc428, 0x3c8c5b6b063b7462,
    0x3fc4e7ea4dc5f27b, 0x3c5949db2ac072fc, 0x3fef91ff40374d01, 0xbc67d03f4d3a9e4c,
    0x3fc5e44fcfa126f3, 0xbc66f443063f89b6, 0x3fef874c2e1eecf6, 0xbc8c6514e1332b16,
    0x3fc6e05dc05a4d4c, 0xbbd32c5c8b81c940, 0x3fef7c1afeffde24, 0xbc78f55bc47540b1,
    0x3fc7dc102fbaf2b5, 0x3c45ab50e23c97c3, 0x3fef706bdf9ece1c, 0xbc8698c80c36dcb4,
    0x3fc8d7632efaa944, 0xbc620fa262cbb953, 0x3fef643efeb82acd, 0x3c76b00ac1fe28ac,
    0x3fc9d252d0cec312, 0x3c59c43d80b1137d, 0x3fef57948cff6797, 0x3c6e3a0d3e03b1d5,
    0x3fcaccdb297a0765, 0xbc59883b57d6cdeb, 0x3fef4a6cbd1e3a79, 0x3c813df0edaebb57,
    0x3fcbc6f84edc6199, 0x3c69c1a56a7b0cab, 0x3fef3cc7c3b3d16e, 0xbc621a3ad28a3494,
    0x3fccc0a6588289a3, 0xbc6868d09bc87c6b, 0x3fef2ea5d753ffed, 0x3c8cc4215f56d583,
    0x3fcdb9e15fb5a5d0, 0xbc632e20d6cc6fc2, 0x3fef20073086649f, 0x3c7b940416c1984b,
    0x3fceb2a57f8ae5a3, 0xbc60be06af572ceb, 0x3fef10ec09c5873b, 0x3c8d9072762c1283,
    0x3fcfaaeed4f31577, 0xbc615d88508e32b8, 0x3fef01549f7deea1, 0x3c8d3c1e99e5cafd,
    0x3fd0515cbf65155c, 0xbc79b8c29dfd8ec8, 0x3feef141300d2f26, 0xbc82aa1b08ded372,
    0x3fd0cd00cef36436, 0xbc79fb0a0c93e2b5, 0x3feee0b1fbc0f11c, 0xbc4bfd2380bbc3b1,
    0x3fd14861aa94ddeb, 0xbc6be881b5b615a4, 0x3feecfa744d5efa1, 0xbc556d0a4af541d0,
    0x3fd1c37d64c6b876, 0x3c746076fe0dcff5, 0x3feebe214f76efa8, 0xbc802f9f12ba543e,
    0x3fd23e52111aaf36, 0xbc74f080334eff18, 0x3feeac2061bbaf4f, 0x3c62c1d53e94658d,
    0x3fd2b8ddc43eb49f, 0x3c61553899f2d807, 0x3fee99a4c3a7cd83, 0xbc82264b1bc53ce8,
    0x3fd3331e94049f87, 0x3c7e0cb6b40c302c, 0x3fee86aebf29a9ed, 0x3c89397afdbb58a7,
    0x3fd3ad129769d3d8, 0x3c003d5504878398, 0x3fee733ea0193d40, 0xbc86428b3546ce13,
    0x3fd426b7e69ee697, 0xbc7f09c75705c59f, 0x3fee5f54b436e9d0, 0x3c87eb0fd02fc8bc,
    0x3fd4a00c9b0f3d20, 0x3c7823ba6bb08ead, 0x3fee4af14b2a449c, 0xbc868ca02e8a6833,
    0x3fd5190ecf68a77a, 0x3c7b357155eef0f3, 0x3fee3614b680d6a5, 0xbc727793aa015237,
    0x3fd591bc9fa2f597, 0x3c67c74bac3fe0cb, 0x3fee20bf49acd6c1, 0xbc5660aec7ef636c,
    0x3fd60a1429078775, 0x3c5b1fd80ba89133, 0x3fee0af15a03dbce, 0x3c5fe8e702771ae6,
    0x3fd682138a38d7f7, 0xbc7d889202444aad, 0x3fedf4ab3ebd875e, 0xbc8e2d8a7e6736c4,
    0x3fd6f9b8e33a0255, 0x3c742bc14ee9da0d, 0x3feddded50f228d6, 0xbc6e80c8d42ba2bf,
    0x3fd7710255764214, 0xbc66ead7314bb6ce, 0x3fedc6b7eb995912, 0x3c54b364776dcd35,
    0x3fd7e7ee03c86d4e, 0xbc7b63bcdabf5af2, 0x3fedaf0b6b888e83, 0x3c8a249e2b5e5cea,
    0x3fd85e7a12826949, 0x3c78a40e9b5face0, 0x3fed96e82f71a9dc, 0x3c8ff61bd5d2039d,
    0x3fd8d4a4a774992f, 0x3c744a02ea766326, 0x3fed7e4e97e17b4a, 0xbc63b770352bed94,
    0x3fd94a6be9f546c5, 0xbc769ce13e683f58, 0x3fed653f073e4040, 0xbc876236434bec37,
    0x3fd9bfce02e80510, 0x3c709e39a320b0a4, 0x3fed4bb9e1c619e0, 0x3c8f34bb77858f61,
    0x3fda34c91cc50cca, 0xbc5a310e3b50cecd, 0x3fed31bf8d8d7c06, 0x3c7e60dd3089cbdd,
    0x3fdaa95b63a09277, 0xbc66293eb13c0381, 0x3fed1750727d94f0, 0x3c80d52b1ec1a48e,
    0x3fdb1d8305321617, 0xbc7ae242cb99f519, 0x3fecfc6cfa52ad9f, 0x3c88b5b5508f2a0d,
    0x3fdb913e30dbac43, 0xbc7e38ad2f6c3ff1, 0x3fece115909a82e5, 0x3c81f139bb31109a,
    0x3fdc048b17b140a3, 0x3c619fe6757e9fa7, 0x3fecc54aa2b2972e, 0x3c64ee162ba83a98,
    0x3fdc7767ec7fd19e, 0xbc5eb14d1a3d5826, 0x3feca90c9fc67d0b, 0xbc646a81485e3462,
    0x3fdce9d2e3d4a51f, 0xbc62fc8a12dae298, 0x3fec8c5bf8ce1a84, 0x3c7ab3d1a1590123,
    0x3fdd5bca34047661, 0x3c728a44a75fc29c, 0x3fec6f39208be53b, 0xbc8741dbfbaadb42,
    0x3fddcd4c15329c9a, 0x3c70d4c6e171fd9a, 0x3fec51a48b8b175e, 0xbc61bbb43b9aa880,
    0x3fde3e56c1582a69, 0xbc50a4821099f88f, 0x3fec339eb01ddd81, 0xbc8caaf5ee82c5c0,
    0x3fdeaee8744b05f0, 0xbc5789b43c9b027d, 0x3fec1528065b7d50, 0xbc8892111312e828,
    0x3fdf1eff6bc4f97b, 0x3c717212f8a7525c, 0x3febf641081e7536, 0x3c8b7bd71628a9a1,
    0x3fdf8e99e76abc97, 0x3c59d950af2d00a3, 0x3febd6ea310294f5, 0x3c731bbcc88c109d,
    0x3fdffdb628d2f57a, 0x3c6f4a992e905b6a, 0x3febb723fe630f32, 0x3c772bd2452d0a39,
    0x3fe0362939c69955, 0xbc82d8cd78397b01, 0x3feb96eeef58840e, 0x3c545a3cc78fade0,
    0x3fe06d3686946e5b, 0x3c83f5ae4538ff1b, 0x3feb764b84b704c2, 0xbc8f5848c21b389b,
    0x3fe0a4021e9e1001, 0xbc86f643a13914f6, 0x3feb553a410c104e, 0x3c58ff7947027a16,
    0x3fe0da8b26b5672e, 0xbc8a58def0bee909, 0x3feb33bba89c8948, 0x3c8ea6a51d1f6ca9,
    0x3fe110d0c4b69c3b, 0x3c8d918998809981, 0x3feb11d04162a4c6, 0x3c71dd561efbc0c2,
    0x3fe146d21f8b7f82, 0x3c7bf9535e2739a8, 0x3feaef78930bd275, 0xbc7f836279746f94,
    0x3fe17c8e5f2eedb0, 0x3c635e57102e2488, 0x3feaccb526f69de5, 0x3c88fb6a8dd6b6cc,
    0x3fe1b204acb02fdd, 0xbc5f190c70cbb5ff, 0x3feaa98688308913, 0xbc0b83d607cd5070,
    0x3fe1e7343236574c, 0x3c722a3fa4f41d5a, 0x3fea85ed4373e02d, 0x3c69be06385ec792,
    0x3fe21c1c1b0394cf, 0x3c5e5b324b23aa31, 0x3fea61e9e72586af, 0x3c858330e2fd453f,
    0x3fe250bb93788bbb, 0x3c7ea3d02457bcce, 0x3fea3d7d0352bdcf, 0xbc868dbaeca19669,
    0x3fe28511c917a067, 0xbc801df1d9a16b70, 0x3fea18a729aee445, 0x3c395e25736c0358,
    0x3fe2b91dea88421e, 0xbc8fa371db216ab0, 0x3fe9f368ed912f85, 0xbc81d200c5791606,
    0x3fe2ecdf279a3082, 0x3c8d3557e0e7e37e, 0x3fe9cdc2e3f25e5c, 0x3c83f99112993f62,
    0x3fe32054b148bc4f, 0x3c8f6b42095a135b, 0x3fe9a7b5a36a6514, 0x3c8722cfcc9fa7a9,
    0x3fe3537db9be0367, 0x3c6b327e7af040f0, 0x3fe98141c42e1310, 0x3c8d1ff80488f08d,
    0x3fe386597456282b, 0xbc710fada93b07a8, 0x3fe95a67e00cb1fd, 0xbc80befda21f862d,
    0x3fe3b8e715a2840a, 0xbc797653a7d2f07b, 0x3fe93328926d9e92, 0xbc8bb77003600cda,
    0x3fe3eb25d36cd53a, 0xbc5be570e1570fc0, 0x3fe90b84784ddaf7, 0xbc70feb10ab93b87,
    0x3fe41d14e4ba6790, 0x3c84608fd287ecf5, 0x3fe8e37c303d9ad1, 0xbc6463a4b53d4bf8,
    0x3fe44eb381cf386b, 0xbc83ed6c1e6a5505, 0x3fe8bb105a5dc900, 0x3c8863e03e9474c1,
    0x3fe48000e431159f, 0xbc8b194a7463ed10, 0x3fe89241985d871f, 0x3c8c48d9c413ed84,
    0x3fe4b0fc46aab761, 0x3c20da05738cc59a, 0x3fe869108d77a6c6, 0x3c7338ffe2bfe9dd,
    0x3fe4e1a4e54ed51b, 0xbc8a492f89b7c76a, 0x3fe83f7dde701ca0, 0xbc4152cf609bc6e8,
    0x3fe511f9fd7b351c, 0xbc85c0e861c48831, 0x3fe8158a31916d5d, 0xbc6de8b90b8228de,
    0x3fe541facddbb724, 0x3c7232c28520d391, 0x3fe7eb362eaa1488, 0x3c5a1d65a4a5959f,
    0x3fe571a6966d59b3, 0x3c5c843b4d0fb198, 0x3fe7c0827f09e54f, 0xbc6c73d6d72aee68,
    0x3fe5a0fc98813a12, 0xbc8d82e2b7d4227b, 0x3fe7956fcd7f6543, 0xbc8ab276e9d45ae4,
    0x3fe5cffc16bf8f0d, 0x3c896cb370eb578a, 0x3fe769fec655211f, 0xbc6827d5cf8c68c5,
    0x3fe5fea4552a9e57, 0x3c80b6cef7ee20b7, 0x3fe73e30174efba1, 0xbc65d3ae3d94ad5f,
    0x3fe62cf49921ac79, 0xbc8edd9855b6241a, 0x3fe712046fa77678, 0x3c8425b0a5029c81,
    0x3fe65aec2963e755, 0x3c8126f96b71053c, 0x3fe6e57c800cf55e, 0x3c860286dedbd0a6,
    0x3fe6888a4e134b2f, 0xbc86b7d37644d5e6, 0x3fe6b898fa9efb5d, 0x3c715ac786ccf4b2,
    0x3fe6b5ce50b7821a, 0xbc65d5158f702e0f, 0x3fe68b5a92eb6253, 0xbc89a91ad985f89c,
    0x3fe6e2b77c40bde1, 0xbc70e729857fad53, 0x3fe65dc1fdeb8cba, 0xbc597c1b47337c77,
    0x3fe70f451d0a8c40, 0x3c697ede3885770d, 0x3fe62fcff20191c7, 0x3c6d9143895756ef,
    0x3fe73b7680dea578, 0xbc72248306dc12a2, 0x3fe6018526f563df, 0x3c846ca5e0e432d0,
    0x3fe7674af6f7b524, 0x3c7e9d3f94ac84a8, 0x3fe5d2e255f1f17a, 0x3c80314104c8892b,
    0x3fe792c1d0041d52, 0xbc8abf05eeb354eb, 0x3fe5a3e839824077, 0x3c8428aa2759be62,
    0x3fe7bdda5e28b3c2, 0x3c4ad1197ccd0393, 0x3fe574978d8e83f2, 0x3c8f4714af282d23,
    0x3fe7e893f5037959, 0x3c80eefbaa650c4c, 0x3fe544f10f592ca5, 0xbc8e7ae8e6c7a62f,
    0x3fe812ede9ae4ba4, 0xbc87830adf402dda, 0x3fe514f57d7bf3da, 0x3c747a108073c259,
    ];
    let mut table = [0; 512];
    let mut i = 0;
    while i < glibc.len() {
        table[i] = glibc[i];
        i += 1;
    }
    table
};

#[inline(always)]
fn entry(j: usize) -> f64 {
    f64::from_bits(TABLE[j & 511])
}

/// The high word of `|x|`, which glibc compares against its range limits.
#[inline(always)]
fn high_word(x: f64) -> u32 {
    ((x.to_bits() >> 32) as u32) & 0x7fff_ffff
}

/// True where the inline computation applies: `2^-27 <= |x| < 0.855469` (no NaN, no inf).
#[inline(always)]
fn in_range(x: f64) -> bool {
    (TINY_HIGH_WORD..RANGE_HIGH_WORD).contains(&high_word(x))
}

/// glibc's `do_sin(x, 0)` and `do_cos(x, 0)` for `x` in range, operation for operation as
/// in `__sincos_fma` (each `mul_add` below is one of its `vfmadd`/`vfnmadd` instructions,
/// every other operation is rounded on its own). Branch-free, so loops over it vectorise.
#[inline(always)]
fn kernel(x: f64) -> (f64, f64) {
    let ax = x.abs();
    // u = big + |x|; its low word is the table row of the nearest multiple of 1/128.
    let u = BIG + ax;
    let j = ((u.to_bits() as usize) & 0x7f) << 2;
    let (sn, ssn, cs, ccs) = (entry(j), entry(j + 1), entry(j + 2), entry(j + 3));
    let xr = ax - (u - BIG);

    // sin, |x| < 0.126: TAYLOR_SIN(x*x, x, 0) = x + ((P(xx)*x - 0.5*0)*xx + 0).
    let xx = x * x;
    let p = xx.mul_add(xx.mul_add(xx.mul_add(xx.mul_add(S5, S4), S3), S2), S1);
    let sin_taylor = x + xx.mul_add(x.mul_add(p, -0.0), 0.0);

    // sin, table: s = xr + (dx + xr*rr*(sn3 + rr*sn5)), c = xr*dx + rr*(cs2 + ...),
    // cor = (ssn + s*ccs - sn*c) + cs*s, sin = copysign(sn + cor, x).
    let dx = if x > 0.0 { 0.0 } else { -0.0 };
    let rr = xr * xr;
    let s = (xr * rr).mul_add(rr.mul_add(SN5, SN3), dx) + xr;
    let c = dx.mul_add(xr, rr * rr.mul_add(CS6, CS4).mul_add(rr, CS2));
    let cor = s.mul_add(cs, (-c).mul_add(sn, s.mul_add(ccs, ssn)));
    let sin_table = (cor + sn).copysign(x);
    let sin = if ax < TAYLOR_LIMIT {
        sin_taylor
    } else {
        sin_table
    };

    // cos, always the table: xc = xr + dx, s = xc + xc*rr*(sn3 + rr*sn5),
    // c = rr*(cs2 + ...), cor = (ccs - s*ssn - cs*c) - sn*s, cos = cs + cor.
    let dx = if x < 0.0 { -0.0 } else { 0.0 };
    let xc = dx + xr;
    let rr = xc * xc;
    let s = (xc * rr).mul_add(rr.mul_add(SN5, SN3), xc);
    let c = rr * rr.mul_add(CS6, CS4).mul_add(rr, CS2);
    let cor = (-s).mul_add(sn, (-c).mul_add(cs, (-ssn).mul_add(s, ccs)));
    (sin, cor + cs)
}

/// libm's `sin` and `cos`, each called on its own as Python's `math.sin`/`math.cos` are.
#[inline(never)]
pub fn libm_sin_cos(x: f64) -> (f64, f64) {
    let x = std::hint::black_box(x);
    (x.sin(), std::hint::black_box(x).cos())
}

/// Why [`sin_cos`] calls libm on this machine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LibmReason {
    /// Not x86-64 Linux with glibc: the inline computation copies glibc's.
    NotGlibcX86_64,
    /// The CPU lacks x86-64-v3 (AVX2 and FMA among it): without FMA and AVX2 glibc runs
    /// its non-FMA build, which the inline path does not copy.
    NoFmaAvx2,
    /// `PPO_TUTOR_LIBM_SINCOS` is set.
    Requested,
    /// The self-check found an angle where the inline result differs from libm's.
    SelfCheckFailed {
        /// The first angle that differed.
        angle: f64,
    },
}

impl std::fmt::Display for LibmReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LibmReason::NotGlibcX86_64 => f.write_str("not x86-64 Linux with glibc"),
            LibmReason::NoFmaAvx2 => f.write_str("the CPU lacks x86-64-v3 (AVX2, FMA)"),
            LibmReason::Requested => f.write_str("PPO_TUTOR_LIBM_SINCOS is set"),
            LibmReason::SelfCheckFailed { angle } => {
                write!(f, "the self-check differs from libm at x = {angle:e}")
            }
        }
    }
}

/// Which implementation [`sin_cos`] and [`sin_cos_slice`] use on this machine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Backend {
    /// glibc's computation, inlined (angles out of its range still call libm).
    Inline,
    /// libm for every angle, and why.
    Libm(LibmReason),
}

impl std::fmt::Display for Backend {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Backend::Inline => f.write_str("inline copy of glibc's sin/cos (FMA build)"),
            Backend::Libm(why) => write!(f, "libm ({why})"),
        }
    }
}

/// What [`decide`] found, once per process.
#[derive(Clone, Copy)]
struct Decision {
    backend: Backend,
    /// The instruction set token the inline path runs under: `pulp`'s x86-64-v3 (AVX2 and
    /// FMA, so each `mul_add` is one instruction), present exactly when `backend` is
    /// [`Backend::Inline`].
    #[cfg(target_arch = "x86_64")]
    token: Option<pulp::x86::V3>,
}

impl Decision {
    fn libm(why: LibmReason) -> Self {
        Self {
            backend: Backend::Libm(why),
            #[cfg(target_arch = "x86_64")]
            token: None,
        }
    }
}

#[inline(always)]
fn decision() -> Decision {
    static DECISION: std::sync::OnceLock<Decision> = std::sync::OnceLock::new();
    *DECISION.get_or_init(decide)
}

/// The implementation in use, decided once per process (the self-check runs then).
pub fn backend() -> Backend {
    decision().backend
}

/// Angles the self-check compares: table rows and their midpoints, both sides of the
/// Taylor limit, the ends of the range, and seeded random angles in CartPole's range.
pub fn self_check_angles() -> Vec<f64> {
    let mut angles = Vec::with_capacity(4096);
    for i in 0..110 {
        let centre = f64::from(i) / 128.0;
        for v in [centre, centre + 1.0 / 256.0] {
            for w in [
                v,
                f64::from_bits(v.to_bits() + 1),
                f64::from_bits(v.to_bits().saturating_sub(1)),
            ] {
                angles.extend([w, -w]);
            }
        }
    }
    for edge in [
        TAYLOR_LIMIT,
        f64::from_bits(0x3e40_0000_0000_0000),
        0.855_468,
    ] {
        for d in 0..8u64 {
            for v in [
                f64::from_bits(edge.to_bits() + d),
                f64::from_bits(edge.to_bits() - d),
            ] {
                angles.extend([v, -v]);
            }
        }
    }
    // Seeded angles: in (-0.3, 0.3), CartPole's, and across the whole range.
    let mut rng = NumpyRng::from_seed(0x5eed);
    while angles.len() < 4096 {
        let span = if angles.len() % 2 == 0 { 0.3 } else { 0.855 };
        angles.push(rng.uniform(-span, span));
    }
    angles
}

#[allow(unreachable_code)]
fn decide() -> Decision {
    if std::env::var_os("PPO_TUTOR_LIBM_SINCOS").is_some() {
        return Decision::libm(LibmReason::Requested);
    }
    #[cfg(all(target_arch = "x86_64", target_os = "linux", target_env = "gnu"))]
    {
        // x86-64-v3 includes FMA and AVX2, glibc's condition for its FMA build.
        let Some(v3) = pulp::x86::V3::try_new() else {
            return Decision::libm(LibmReason::NoFmaAvx2);
        };
        for x in self_check_angles().into_iter().filter(|&x| in_range(x)) {
            // Straight to the inline path: `dispatch` asks for the decision made here.
            let inline = pulp::Simd::vectorize(v3, Wrap(Angle(x)));
            let (s, c) = libm_sin_cos(x);
            if inline.0.to_bits() != s.to_bits() || inline.1.to_bits() != c.to_bits() {
                return Decision::libm(LibmReason::SelfCheckFailed { angle: x });
            }
        }
        return Decision {
            backend: Backend::Inline,
            token: Some(v3),
        };
    }
    Decision::libm(LibmReason::NotGlibcX86_64)
}

/// The kernel over slices, then libm for the angles out of its range. The slices are
/// arguments, so the compiler knows they do not overlap (it vectorises the loop only then).
#[inline(always)]
fn fill(x: &[f64], sin: &mut [f64], cos: &mut [f64]) {
    let n = x.len().min(sin.len()).min(cos.len());
    let (x, sin, cos) = (&x[..n], &mut sin[..n], &mut cos[..n]);
    for i in 0..n {
        (sin[i], cos[i]) = kernel(x[i]);
    }
    for i in 0..n {
        if !in_range(x[i]) {
            (sin[i], cos[i]) = libm_sin_cos(x[i]);
        }
    }
}

/// One angle's sine and cosine, as work for [`dispatch`].
struct Angle(f64);

impl WithMath for Angle {
    type Output = (f64, f64);
    #[inline(always)]
    fn run<M: Math>(self, math: M) -> Self::Output {
        math.sin_cos(self.0)
    }
}

/// `(sin x, cos x)`, equal bit for bit to libm's `sin(x)` and `cos(x)`.
#[inline(always)]
#[must_use]
pub fn sin_cos(x: f64) -> (f64, f64) {
    // Angles out of range go to libm inside `Inline::sin_cos`.
    dispatch(Angle(x))
}

/// [`sin_cos`] of every angle in `x`, written to `sin` and `cos` (vectorised on the
/// inline path).
///
/// # Panics
/// If the three slices differ in length.
pub fn sin_cos_slice(x: &[f64], sin: &mut [f64], cos: &mut [f64]) {
    /// Many angles.
    struct Angles<'a>(&'a [f64], &'a mut [f64], &'a mut [f64]);
    impl WithMath for Angles<'_> {
        type Output = ();
        #[inline(always)]
        fn run<M: Math>(self, math: M) {
            math.sin_cos_slice(self.0, self.1, self.2);
        }
    }
    assert!(
        x.len() == sin.len() && x.len() == cos.len(),
        "sin_cos_slice: lengths differ"
    );
    dispatch(Angles(x, sin, cos));
}

/// A way to compute CartPole's sin, cos and division with Python's bits: code generic
/// over it is compiled once per way.
pub trait Math: Copy {
    /// `(sin x, cos x)`, bit for bit libm's.
    fn sin_cos(self, x: f64) -> (f64, f64);

    /// `a / by`, rounded to nearest as every IEEE division is.
    #[inline(always)]
    fn divide(self, a: f64, by: Divisor) -> f64 {
        a / by.value()
    }

    /// [`Math::sin_cos`] of every angle in `x`, written to `sin` and `cos`.
    #[inline(always)]
    fn sin_cos_slice(self, x: &[f64], sin: &mut [f64], cos: &mut [f64]) {
        for ((&x, s), c) in x.iter().zip(sin.iter_mut()).zip(cos.iter_mut()) {
            (*s, *c) = self.sin_cos(x);
        }
    }
}

/// libm, called for each angle, and the hardware division: correct on every platform.
#[derive(Debug, Clone, Copy)]
pub struct Portable;

impl Math for Portable {
    #[inline(always)]
    fn sin_cos(self, x: f64) -> (f64, f64) {
        libm_sin_cos(x)
    }
}

/// glibc's sin/cos inlined and the proven fast division, compiled with FMA; [`dispatch`]
/// hands it out only where it is valid.
#[derive(Debug, Clone, Copy)]
pub struct Inline(());

impl Math for Inline {
    #[inline(always)]
    fn sin_cos(self, x: f64) -> (f64, f64) {
        if in_range(x) {
            kernel(x)
        } else {
            libm_sin_cos(x)
        }
    }

    #[inline(always)]
    fn sin_cos_slice(self, x: &[f64], sin: &mut [f64], cos: &mut [f64]) {
        fill(x, sin, cos);
    }

    /// The multiply-and-FMA guess, proven per call (see [`super::quotient`]).
    #[inline(always)]
    fn divide(self, a: f64, by: Divisor) -> f64 {
        by.divide(a)
    }
}

/// Work generic over the [`Math`] (as `pulp`'s `WithSimd` is over the instruction set).
pub trait WithMath {
    /// What the work returns.
    type Output;
    /// Does the work; should be `#[inline(always)]`, so that it is compiled with FMA.
    fn run<M: Math>(self, math: M) -> Self::Output;
}

/// Runs the work with [`Inline`] inside `pulp`'s dispatch, so it is compiled with
/// the CPU's instruction set (FMA included).
struct Wrap<W>(W);

impl<W: WithMath> pulp::WithSimd for Wrap<W> {
    type Output = W::Output;

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) -> Self::Output {
        self.0.run(Inline(()))
    }
}

/// Runs `work` with the inline sin/cos, compiled for this CPU, where [`backend`] allows
/// it, and with libm elsewhere.
#[inline(always)]
pub fn dispatch<W: WithMath>(work: W) -> W::Output {
    #[cfg(target_arch = "x86_64")]
    if let Some(v3) = decision().token {
        return pulp::Simd::vectorize(v3, Wrap(work));
    }
    work.run(Portable)
}
