!> Reproducible random numbers, the same on every compiler, platform and thread count.
!>
!> Integer arithmetic is done on 32-bit words held in 64-bit integers, so no operation overflows
!> (signed overflow is undefined in Fortran). Two interfaces:
!>  - `rng_t`, a stream (xoshiro128**), for sequential draws;
!>  - `normal_pair_at`, counter-based (Philox4x32-10): two standard normals that depend only on
!>    (seed, i, j). The surface generator keys each Fourier mode by its signed integer
!>    wavenumber, so the same seed gives the same surface at any grid size that resolves its
!>    spectrum, in any loop order, on any number of threads or ranks.
module veslide_rng
    use veslide_kinds, only: dp, i8, two_pi
    implicit none
    private
    public :: rng_t, normal_pair_at, philox4x32

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
        a = self%next32(); b = self%next32()
        u = uniform53(a, b)
    end function rng_uniform

    !> Standard normal deviate (Box-Muller; the second value of each pair is discarded)
    real(dp) function rng_normal(self) result(z)
        class(rng_t), intent(inout) :: self
        real(dp) :: u1, u2
        u1 = self%uniform(); u2 = self%uniform()
        z = sqrt(-2.0_dp*log(u1))*cos(two_pi*u2)
    end function rng_normal

    !> (a*b) for a, b in [0, 2**32) as its high and low 32-bit words, without overflow
    elemental subroutine mulhilo32(a, b, hi, lo)
        integer(i8), intent(in) :: a, b
        integer(i8), intent(out) :: hi, lo
        integer(i8) :: t1, t2, s
        t1 = a*iand(b, 65535_i8)                   ! < 2**48
        t2 = a*shiftr(b, 16)                       ! < 2**48
        s = t1 + shiftl(iand(t2, 65535_i8), 16)    ! < 2**49
        lo = iand(s, mask32)
        hi = shiftr(t2, 16) + shiftr(s, 32)
    end subroutine mulhilo32

    !> Philox4x32-10 (Salmon, Moraes, Dror, Shaw, SC'11; the Random123 library): four 32-bit
    !> output words, a bijection of the 128-bit counter for each 64-bit key; every output bit
    !> depends on every bit of counter and key. Words are held in [0, 2**32).
    pure function philox4x32(counter, key) result(x)
        integer(i8), intent(in) :: counter(4), key(2)
        integer(i8) :: x(4)
        integer(i8), parameter :: m0 = 3528531795_i8, m1 = 3449720151_i8     ! 0xD2511F53, 0xCD9E8D57
        integer(i8), parameter :: w0 = 2654435769_i8, w1 = 3144134277_i8     ! 0x9E3779B9, 0xBB67AE85
        integer(i8) :: k(2), hi0, lo0, hi1, lo1
        integer :: r
        x = iand(counter, mask32); k = iand(key, mask32)
        do r = 1, 10
            call mulhilo32(m0, x(1), hi0, lo0)
            call mulhilo32(m1, x(3), hi1, lo1)
            x = [ieor(ieor(hi1, x(2)), k(1)), lo1, ieor(ieor(hi0, x(4)), k(2)), lo0]
            k = iand(k + [w0, w1], mask32)
        end do
    end function philox4x32

    !> Uniform double in (0, 1) from two 32-bit words (27 + 26 = 53 random bits)
    elemental real(dp) function uniform53(a, b) result(u)
        integer(i8), intent(in) :: a, b
        u = (real(shiftr(a, 5)*67108864_i8 + shiftr(b, 6), dp) + 0.5_dp)/9007199254740992.0_dp
    end function uniform53

    !> Two independent standard normals determined by (seed, i, j, stream) alone: one Philox
    !> block with counter (i, j, stream, 0) and the seed as key, both uniforms of Box-Muller from
    !> its four words. Signed i, j are taken modulo 2**32.
    pure subroutine normal_pair_at(seed, i, j, z1, z2, stream)
        !> seed
        integer(i8), intent(in) :: seed
        !> integer keys (signed wavenumbers)
        integer, intent(in) :: i, j
        !> the two deviates
        real(dp), intent(out) :: z1, z2
        !> an independent family of draws for the same (seed, i, j) (default 0)
        integer, intent(in), optional :: stream
        integer(i8) :: w(4), ctr(4)
        real(dp) :: u1, u2, r
        ctr = [int(i, i8), int(j, i8), 0_i8, 0_i8]
        if (present(stream)) ctr(3) = int(stream, i8)
        w = philox4x32(ctr, [iand(seed, mask32), iand(shiftr(seed, 32), mask32)])
        u1 = uniform53(w(1), w(2))
        u2 = uniform53(w(3), w(4))
        r = sqrt(-2.0_dp*log(u1))
        z1 = r*cos(two_pi*u2)
        z2 = r*sin(two_pi*u2)
    end subroutine normal_pair_at

end module veslide_rng
