!> Persson's contact and friction theory in its two-dimensional wave-vector form, evaluated on the
!> realised spectrum of one surface.
!>
!> ## Sources
!> B.N.J. Persson, J. Chem. Phys. 115, 3840 (2001) (contact area and rubber friction, isotropic);
!> G. Carbone, B. Lorenz, B.N.J. Persson, A. Wohlers, Eur. Phys. J. E 29, 275 (2009) (anisotropic
!> surfaces, the d^2q form); B.N.J. Persson, J. Phys.: Condens. Matter 18, 7789 (2006) (the
!> correction factor S(q)). Written here without assuming isotropy and re-derived in veslide's
!> conventions (docs/validation.md states the checks).
!>
!> ## Conventions
!> Coordinates fixed to the rigid surface; heights h positive toward the solid; v the velocity of
!> the rigid surface relative to the solid; time dependence exp(+i w t), so mode q is felt by the
!> solid at w = -q.v and the kernel is K(q) = 2(1-nu^2) C(-q.v)/|q| (C the complex compliance).
!> E*(w) = 1/((1-nu^2) C(w)), E*''(w) = Im E*(w) > 0 for w > 0, odd in w. The heights are
!> h(x) = sum_q a_q exp(i q.x) over the full plane of wave-vectors of the periodic cell, a_{-q} =
!> conj(a_q); the continuous spectrum C(q) of the theory is replaced by the realised one through
!> integral d^2q C(q) f(q) -> sum_q |a_q|^2 f(q). Every r2c half-spectrum entry stands for itself and
!> its conjugate partner: weight w = 1 for the column i = 1 (whose partners are stored) and the
!> Nyquist column of an even nx, w = 2 otherwise.
!>
!> ## Equations as implemented
!> Per mode, the full-contact pressure amplitude is p_q = a_q/K(q), so define z(q) = 1/K(q) =
!> |q| E*(-q.v)/2. Then, with p0 the nominal pressure and all sums over modes q /= 0,
!>
!>     G(q)  = (1/(2 p0^2)) sum_{|q'| <= q} |z(q')|^2 |a_q'|^2
!>           = (1/8) integral_{|q'|<q} d^2q' |q'|^2 C(q') |E*(q'.v)|^2 / p0^2
!>     P(q)  = erf( 1 / (2 sqrt(G(q))) )            (P = 1 where G = 0)
!>     S(q)  = 1                                     (default: Persson's original theory)
!>           = 1/2 + P(q)^2/2                        (s_correction = .true.: gamma_S = 1/2, 2006)
!>     F     = sum_q q Im z(q) P(|q|) S(|q|) |a_q|^2
!>           = -(1/2) integral d^2q q |q| P S E*''(q.v) C(q)            [Pa, vector]
!>     friction_coefficient = -F.v_hat/p0,  lateral_force_ratio = F.(z_hat x v_hat)/p0,
!>     contact_area_fraction = P(q_max).
!>
!> G(q) is the cumulative sum over shells of |q|: all modes whose |q|^2 agree to a relative 1e-12
!> form one shell (equal |q| computed along different paths may differ by a few ulps), and the
!> shell's own modes are included in its G, so P(q_max) counts every mode. 2 p0^2 G(q) is the
!> variance of the full-contact pressure of the modes up to q (Persson's diffusion in pressure
!> gives a Gaussian of variance 2 p0^2 G, whence P = erf(1/(2 sqrt G))).
!>
!> ## Sign of the force
!> F is the tangential force of the solid on the rigid surface per nominal area, the same quantity
!> as the kernel's F = <p grad w> = -sum_q q Im K |p_q|^2. In full contact (P = S = 1)
!> p_q = a_q/K, and -Im K/|K|^2 = Im(1/K) = Im z, so the formula above is that force term by term:
!> the test `full-contact-is-exact` checks it against the boundary-element full-contact force of
!> the same surface to round-off. With v along +x, Im z(q) = -(|q|/2) E*''(q.v) has the sign of
!> -q_x, so F_x < 0: friction resists the motion and friction_coefficient > 0. (The note's
!> "F/A = +(1/2) integral ..." is the force on the solid; the sign here is the one the identity fixes.)
!>
!> ## Discrete details
!> K is the case's kernel itself (`kernel_t`, the spectral variant for the continuum theory), and
!> the grid's rules apply (Hermitian weights; Nyquist lines carry no derivative), exactly as in the
!> kernel's `tangential_force`; the full-contact identity then holds for any spectrum. A layer's
!> factor and an interfacial shear's coupling (docs/interface.md) come with the kernel: the theory
!> takes them through z = 1/K, an extension of Persson's, whose published form has neither
!> (the full-contact identity still holds term by term). The direction of sliding is v's, or
!> at v = 0 the shear's; the shear's own part mu_f is added by the output (veslide_quantities).
!> Modes with a_q = 0 contribute nothing and are skipped; `q_per_m` lists only shells with power.
!> Cost: one pass over the half-spectrum and a bucket sort of |q|^2 (one bucket per mode; |q|^2 is close to uniformly
!> distributed on a lattice, so a bucket holds about one shell and is sorted exactly in place):
!> O(N) in all, about the cost of a few FFTs of the grid.
!>
!> ## Known limits of the theory
!> - The diffusion in pressure is an approximation. At small load it gives A/A0 = sqrt(8/pi) p0 /
!>   (E* rms slope), a prefactor 1.6 where boundary-element simulations find about 2 (e.g. Hyun et
!>   al. 2004; Prodanov, Dapp & Mueser 2014): the area is underestimated by some 20%. For a single
!>   wave it gives P = erf(p0/p1) (p1 the full-contact pressure amplitude) where the exact elastic
!>   solution is in full contact for p0 >= p1.
!> - Friction: good up to intermediate speeds; in partial contact it overestimates friction
!>   (Scaraggi & Persson 2014; Sukhomlinov & Mueser 2021): the stress in the contact spots is not the
!>   full-contact stress times P, and S(q) is an ad hoc correction for the elastic relaxation of the
!>   spots. The flash temperature, adhesion and the cut-off q_max (set here by the spectrum itself)
!>   are outside the model.
!> - The estimate uses |E*(q.v)| of the sliding solid also in G: the contact area is that of the
!>   steady sliding state, not of the static one (as in Persson's papers).
module veslide_persson
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use veslide_kinds, only: dp, i8, two_pi
    use veslide_error, only: error_t, fatal_error, ERROR_NUMERICAL
    use veslide_grid, only: grid_t
    use veslide_kernel, only: kernel_t
    implicit none
    private
    public :: persson_t, persson_estimate

    !> Result of one estimate
    type :: persson_t
        real(dp) :: contact_area_fraction = 0.0_dp   !! P(q_max)
        !> tangential force of the solid on the rigid surface per nominal area [Pa], (x, y)
        real(dp) :: force_pa(2) = 0.0_dp
        real(dp) :: friction_coefficient = 0.0_dp    !! -F.v_hat/p0 (0 when v = 0 without shear)
        real(dp) :: lateral_force_ratio = 0.0_dp     !! F.(z_hat x v_hat)/p0
        real(dp), allocatable :: q_per_m(:)          !! distinct |q| shells present in the spectrum, ascending [1/m]
        real(dp), allocatable :: area_fraction(:)    !! P(q) at those shells
    end type persson_t

    character(len=*), parameter :: here = "veslide:persson:persson_estimate: "

    !> relative tolerance within which two |q|^2 are one shell
    real(dp), parameter :: shell_tol = 1.0e-12_dp

contains

    !> Persson's estimate of the contact area and the viscoelastic friction force of steady sliding,
    !> for the heights whose half-spectrum is `hk` on the grid of `kernel`, the operator of the
    !> case's material and velocity. On error `res` is left at its defaults (arrays unallocated).
    subroutine persson_estimate(kernel, hk, p_mean_pa, res, error, s_correction)
        !> the influence operator K(q) of the solid and the sliding velocity (spectral variant)
        type(kernel_t), intent(in) :: kernel
        !> r2c half-spectrum (nx/2+1, ny) of the heights with h(x) = sum over the full plane of
        !> a_q exp(i q.x), i.e. FFTW's unnormalised r2c output divided by nx*ny [m]; q = 0 is ignored
        complex(dp), intent(in) :: hk(:, :)
        !> nominal (mean) contact pressure p0 [Pa]
        real(dp), intent(in) :: p_mean_pa
        !> the estimate
        type(persson_t), intent(out) :: res
        !> error on bad input or a non-finite result
        type(error_t), allocatable, intent(out) :: error
        !> .false. (default): S = 1, the original theory; .true.: S(q) = 1/2 + P(q)^2/2
        logical, intent(in), optional :: s_correction

        logical :: s_corr_
        integer :: i, j, k, m, b, nq, nb, nmode, nshell
        real(dp) :: qd(2), p2, key, kmax, scale, vn, vhat(2), g, p, s, cum, f(2)
        complex(dp) :: z
        integer, allocatable :: start(:)
        real(dp), allocatable :: rec(:, :)
        type(grid_t) :: grid

        s_corr_ = .false.; if (present(s_correction)) s_corr_ = s_correction
        grid = kernel%grid
        nq = grid%nq()
        ! ieee_is_finite first: it raises no flag on a NaN (the suite also runs with -ffpe-trap=invalid)
        if (size(hk, 1) /= nq .or. size(hk, 2) /= grid%ny) then
            call fatal_error(error, here//"hk must have the shape (nx/2+1, ny) of the kernel's grid"); return
        end if
        if (.not. (all(ieee_is_finite(real(hk, dp))) .and. all(ieee_is_finite(aimag(hk))))) then
            call fatal_error(error, here//"hk has non-finite entries"); return
        end if
        if (.not. ieee_is_finite(p_mean_pa)) then
            call fatal_error(error, here//"p_mean_pa must be positive and finite"); return
        end if
        if (.not. p_mean_pa > 0.0_dp) then
            call fatal_error(error, here//"p_mean_pa must be positive and finite"); return
        end if
        if (int(nq, i8)*int(grid%ny, i8) > int(huge(1), i8)) then
            call fatal_error(error, here//"hk is too large: (nx/2+1)*ny must fit a default integer"); return
        end if

        ! ---- shells of |q|: a bucket sort of |k|^2 = (kx/lx)^2 + (ky/ly)^2. On a lattice it is close
        ! to uniformly distributed on [0, kmax], so with one bucket per mode a bucket holds about one
        ! shell; each bucket is then sorted exactly. Pass 1 counts the modes with power per bucket.
        nb = max(nq*grid%ny - 1, 1)
        kmax = (real(grid%nx/2, dp)/grid%lx_m)**2 + (real(grid%ny/2, dp)/grid%ly_m)**2
        scale = 0.0_dp
        if (kmax > 0.0_dp) scale = real(nb, dp)/kmax
        allocate (start(0:nb))
        start = 0
        do j = 1, grid%ny
            do i = 1, nq
                if (i == 1 .and. j == 1) cycle
                if (.not. (real(hk(i, j), dp)**2 + aimag(hk(i, j))**2 > 0.0_dp)) cycle
                b = bucket(key_of(i, j))
                start(b + 1) = start(b + 1) + 1
            end do
        end do
        do b = 1, nb
            start(b) = start(b) + start(b - 1)
        end do
        nmode = start(nb)

        ! ---- pass 2: one record per mode with power, (|k|^2, w |z|^2 |a|^2, w Im z |a|^2 q_d), with
        ! z = 1/K, q_d the derivative wavevector, written to the mode's place in its bucket (one record,
        ! not four arrays: one cache line per scattered write)
        allocate (rec(4, nmode))
        do j = 1, grid%ny
            do i = 1, nq
                if (i == 1 .and. j == 1) cycle
                p2 = real(hk(i, j), dp)**2 + aimag(hk(i, j))**2
                if (.not. (p2 > 0.0_dp)) cycle
                p2 = grid%hermitian_weight(i)*p2
                z = 1.0_dp/kernel%value(i, j)
                qd = grid%derivative_wavevector(i, j)
                key = key_of(i, j)
                b = bucket(key)
                m = start(b) + 1; start(b) = m          ! start(b) now counts through bucket b
                rec(1, m) = key
                rec(2, m) = p2*(real(z, dp)**2 + aimag(z)**2)
                rec(3:4, m) = p2*aimag(z)*qd
            end do
        end do

        ! ---- exact order within the buckets (bucket b now ends at start(b)), then one shell per
        ! |q|^2 (equal within shell_tol), summed in place: shell k overwrites rec(:, k), k <= m
        do b = 0, nb - 1
            k = 0; if (b > 0) k = start(b - 1)
            if (start(b) - k > 1) call sort_segment(rec(:, k + 1:start(b)))
        end do
        nshell = 0
        do m = 1, nmode
            if (nshell > 0) then
                if (rec(1, m) <= rec(1, nshell)*(1.0_dp + shell_tol)) then
                    rec(2:4, nshell) = rec(2:4, nshell) + rec(2:4, m)
                    cycle
                end if
            end if
            nshell = nshell + 1
            rec(:, nshell) = rec(:, m)
        end do

        ! ---- cumulative G, P, S and the force
        allocate (res%q_per_m(nshell), res%area_fraction(nshell))
        cum = 0.0_dp
        f = 0.0_dp
        p = 1.0_dp
        do k = 1, nshell
            cum = cum + rec(2, k)
            g = cum/(2.0_dp*p_mean_pa**2)
            if (g > 0.0_dp) then
                p = erf(0.5_dp/sqrt(g))
            else
                p = 1.0_dp
            end if
            s = 1.0_dp
            if (s_corr_) s = 0.5_dp + 0.5_dp*p*p
            f = f + p*s*rec(3:4, k)
            res%q_per_m(k) = two_pi*sqrt(rec(1, k))
            res%area_fraction(k) = p
        end do
        res%contact_area_fraction = p
        res%force_pa = f
        ! the direction of sliding: the velocity's, or at v = 0 an interfacial shear's (it is
        ! along v_hat, and the coupling it brings is a force at any speed)
        vhat = kernel%velocity_m_s
        if (.not. norm2(vhat) > 0.0_dp) vhat = kernel%shear
        vn = norm2(vhat)
        if (vn > 0.0_dp) then
            vhat = vhat/vn
            res%friction_coefficient = -dot_product(f, vhat)/p_mean_pa
            res%lateral_force_ratio = (-f(1)*vhat(2) + f(2)*vhat(1))/p_mean_pa
        end if
        if (.not. (ieee_is_finite(cum) .and. all(ieee_is_finite(f)))) then
            call fatal_error(error, here//"non-finite result (overflow): check the units of hk and p_mean_pa", &
                             ERROR_NUMERICAL)
            return
        end if

    contains

        !> |k|^2 = (kx/lx)^2 + (ky/ly)^2 of entry (i, j) [1/m^2]: the sort key, |q|^2/(2 pi)^2
        pure real(dp) function key_of(i, j) result(kq)
            integer, intent(in) :: i, j
            integer :: kn(2)
            kn = grid%wavenumber(i, j)
            kq = (real(kn(1), dp)/grid%lx_m)**2 + (real(kn(2), dp)/grid%ly_m)**2
        end function key_of

        !> bucket 0..nb-1 of a |q|^2 key (monotone in the key)
        pure integer function bucket(kq) result(bk)
            real(dp), intent(in) :: kq
            bk = min(int(kq*scale), nb - 1)
        end function bucket

    end subroutine persson_estimate

    !> Sort the records of one bucket by their key rec(1, :): insertion sort when short (a bucket
    !> holds about one shell), a radix sort of the keys' bit patterns otherwise
    pure subroutine sort_segment(rec)
        real(dp), intent(inout) :: rec(:, :)
        integer, allocatable :: order(:)
        real(dp) :: t(size(rec, 1))
        integer :: i, j, n
        n = size(rec, 2)
        if (n <= 32) then
            do i = 2, n
                if (rec(1, i) >= rec(1, i - 1)) cycle
                t = rec(:, i)
                j = i - 1
                do while (j >= 1)
                    if (rec(1, j) <= t(1)) exit
                    rec(:, j + 1) = rec(:, j)
                    j = j - 1
                end do
                rec(:, j + 1) = t
            end do
        else
            allocate (order(n))
            call radix_order(transfer(rec(1, :), 0_i8, n), order)   ! positive doubles sort as their bit patterns
            rec = rec(:, order)
        end if
    end subroutine sort_segment

    !> Stable ascending order of non-negative 64-bit keys: LSD radix sort, 8-bit digits (used for the
    !> rare crowded bucket, e.g. a cell much longer in x than in y, where a row of modes falls in one)
    pure subroutine radix_order(key, order)
        !> keys (non-negative)
        integer(i8), intent(in) :: key(:)
        !> permutation: key(order) is ascending
        integer, intent(out) :: order(:)
        integer, parameter :: nb = 8, nbucket = 2**nb
        integer(i8), allocatable :: kcur(:), knew(:)
        integer, allocatable :: onew(:), cnt(:)
        integer :: n, k, d, pass, pos, total, c
        n = size(key)
        order = [(k, k=1, n)]
        if (n < 2) return
        kcur = key
        allocate (knew(n), onew(n), cnt(0:nbucket - 1))
        do pass = 0, 64/nb - 1
            cnt = 0
            do k = 1, n
                d = int(ibits(kcur(k), nb*pass, nb))
                cnt(d) = cnt(d) + 1
            end do
            if (maxval(cnt) == n) cycle           ! one digit value: the pass changes nothing
            total = 0
            do d = 0, nbucket - 1
                c = cnt(d); cnt(d) = total; total = total + c
            end do
            do k = 1, n
                d = int(ibits(kcur(k), nb*pass, nb))
                pos = cnt(d) + 1; cnt(d) = pos
                knew(pos) = kcur(k); onew(pos) = order(k)
            end do
            kcur = knew; order = onew
        end do
    end subroutine radix_order

end module veslide_persson
