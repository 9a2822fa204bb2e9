!> Reproducible random numbers, the same on every compiler, platform and thread count.
!>
!> Integer arithmetic is done on 32-bit words held in 64-bit integers, so no operation overflows
!> (signed overflow is undefined in Fortran). Two interfaces:
!>  - `rng_t`, a stream (xoshiro128**), for sequential draws;
!>  - `normal_pair_at`, counter-based: two standard normals that depend only on (seed, i, j).
!>    The surface generator keys each Fourier mode by its signed integer wavenumber, so the same
!>    seed gives the same surface at any grid size that resolves its spectrum, in any loop order.
module veslide_rng
    use veslide_kinds, only: dp, i8, two_pi
    implicit none
    private
    public :: rng_t, normal_pair_at

    integer(i8), parameter :: mask32 = 4294967295_i8

    !> xoshiro128** stream; four 32-bit words of state
    type :: rng_t
        integer(i8) :: s(4) = [1_i8, 2_i8, 3_i8, 4_i8]   !! state words, each in [0, 2**32)
    contains
        procedure :: seed => rng_seed
        procedure :: next32 => rng_next32
        procedure :: uniform => rng_uniform
        procedure :: normal => rng_normal
    end type rng_t

contains

    !> (a*b) mod 2**32 for a, b in [0, 2**32), without overflow
    elemental integer(i8) function mul32(a, b) result(r)
        integer(i8), intent(in) :: a, b
        integer(i8) :: lo, hi
        lo = a*iand(b, 65535_i8)                 ! < 2**48
        hi = iand(a*shiftr(b, 16), 65535_i8)     ! only the low 16 bits survive the shift by 16
        r = iand(lo + shiftl(hi, 16), mask32)
    end function mul32

    elemental integer(i8) function rotl32(x, k) result(r)
        integer(i8), intent(in) :: x
        integer, intent(in) :: k
        r = iand(ior(shiftl(x, k), shiftr(x, 32 - k)), mask32)
    end function rotl32

    !> MurmurHash3's 32-bit finaliser: a bijective avalanche mixer
    elemental integer(i8) function fmix32(x0) result(x)
        integer(i8), intent(in) :: x0
        x = iand(x0, mask32)
        x = ieor(x, shiftr(x, 16)); x = mul32(x, 2246822507_i8)
        x = ieor(x, shiftr(x, 13)); x = mul32(x, 3266489909_i8)
        x = ieor(x, shiftr(x, 16))
    end function fmix32

    !> Seed the stream from a 64-bit integer (any value)
    pure subroutine rng_seed(self, seed)
        class(rng_t), intent(inout) :: self
        !> seed
        integer(i8), intent(in) :: seed
        integer(i8) :: lo, hi
        lo = iand(seed, mask32); hi = iand(shiftr(seed, 32), mask32)
        self%s(1) = fmix32(ieor(lo, 2654435769_i8))
        self%s(2) = fmix32(ieor(hi, 1013904242_i8) + 1_i8)
        self%s(3) = fmix32(ieor(lo, 3668340011_i8) + 2_i8)
        self%s(4) = fmix32(ieor(hi, 2027808484_i8) + 3_i8)
        if (all(self%s == 0)) self%s(1) = 1_i8
    end subroutine rng_seed

    !> Next 32-bit output, in [0, 2**32)
    integer(i8) function rng_next32(self) result(r)
        class(rng_t), intent(inout) :: self
        integer(i8) :: t
        r = mul32(rotl32(mul32(self%s(2), 5_i8), 7), 9_i8)
        t = iand(shiftl(self%s(2), 9), mask32)
        self%s(3) = ieor(self%s(3), self%s(1))
        self%s(4) = ieor(self%s(4), self%s(2))
        self%s(2) = ieor(self%s(2), self%s(3))
        self%s(1) = ieor(self%s(1), self%s(4))
        self%s(3) = ieor(self%s(3), t)
        self%s(4) = rotl32(self%s(4), 11)
    end function rng_next32

    !> Uniform double in (0, 1) with 53 random bits
    real(dp) function rng_uniform(self) result(u)
        class(rng_t), intent(inout) :: self
        integer(i8) :: a, b
        a = shiftr(self%next32(), 5)     ! 27 bits
        b = shiftr(self%next32(), 6)     ! 26 bits
        u = (real(a*67108864_i8 + b, dp) + 0.5_dp)/9007199254740992.0_dp
    end function rng_uniform

    !> Standard normal deviate (Box-Muller; the second value of each pair is discarded)
    real(dp) function rng_normal(self) result(z)
        class(rng_t), intent(inout) :: self
        real(dp) :: u1, u2
        u1 = self%uniform(); u2 = self%uniform()
        z = sqrt(-2.0_dp*log(u1))*cos(two_pi*u2)
    end function rng_normal

    !> Two independent standard normals determined by (seed, i, j) alone
    pure subroutine normal_pair_at(seed, i, j, z1, z2)
        !> seed
        integer(i8), intent(in) :: seed
        !> integer keys (signed wavenumbers)
        integer, intent(in) :: i, j
        !> the two deviates
        real(dp), intent(out) :: z1, z2
        integer(i8) :: w(4), a, b
        real(dp) :: u1, u2, r
        integer(i8) :: ki, kj
        ki = iand(int(i, i8), mask32); kj = iand(int(j, i8), mask32)
        w(1) = fmix32(ieor(iand(seed, mask32), fmix32(ki + 1640531527_i8)))
        w(2) = fmix32(ieor(iand(shiftr(seed, 32), mask32), fmix32(kj + 3291469857_i8)))
        w(3) = fmix32(ieor(w(1), w(2)) + 2246822519_i8)
        w(4) = fmix32(ieor(w(2), rotl32(w(1), 13)) + 374761393_i8)
        a = shiftr(w(1), 5); b = shiftr(w(2), 6)
        u1 = (real(a*67108864_i8 + b, dp) + 0.5_dp)/9007199254740992.0_dp
        a = shiftr(w(3), 5); b = shiftr(w(4), 6)
        u2 = (real(a*67108864_i8 + b, dp) + 0.5_dp)/9007199254740992.0_dp
        r = sqrt(-2.0_dp*log(u1))
        z1 = r*cos(two_pi*u2)
        z2 = r*sin(two_pi*u2)
    end subroutine normal_pair_at

end module veslide_rng
