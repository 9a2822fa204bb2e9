!> Materials: complex compliance of the Prony laws, their limits, signs and equivalences, and
!> the refusal of bad constants
module test_veslide_material
    use veslide_kinds, only: dp
    use, intrinsic :: iso_fortran_env, only: qp => real128
    use veslide_material, only: material_t, new_elastic, new_one_term, new_creep, new_relaxation, layer_factor, &
                                BASE_BONDED, BASE_FRICTIONLESS, shift_factor, pchip_value
    use veslide_lapack, only: dgesv
    use testsuite, only: error_t, unittest_t, new_unittest, check, report
    use reference_oracles, only: paper_solid, einf, tau
    implicit none
    private
    public :: collect_material

contains

    subroutine collect_material(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("compliance-limits-and-sign", test_compliance), &
            new_unittest("relaxation-equals-creep", test_relaxation_creep), &
            new_unittest("elastic-is-frequency-independent", test_elastic), &
            new_unittest("loss-peak-of-the-standard-solid", test_loss_peak), &
            new_unittest("compliance-of-200-terms-over-40-decades", test_long_series), &
            new_unittest("windowed-compliance-is-the-term-by-term-sum", test_windowed_sum), &
            new_unittest("shift-table-of-wlf-values-is-wlf", test_table_is_wlf), &
            new_unittest("pchip-as-scipy", test_pchip_scipy), &
            new_unittest("layer-factor-against-the-boundary-value-problem", test_layer_bvp), &
            new_unittest("layer-factor-limits", test_layer_limits), &
            new_unittest("creep-sum-must-stay-below-1/E0", test_creep_sum, should_fail=.true., &
                         expect="sum of c_k must be below 1/E0"), &
            new_unittest("poisson-out-of-range", test_bad_poisson, should_fail=.true., expect="poisson") &
            ]
    end subroutine collect_material

    subroutine test_compliance(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        complex(dp) :: c
        integer :: k
        call paper_solid(11.0_dp, m, error); if (allocated(error)) return
        call check(error, real(m%compliance(0.0_dp), dp), 11.0_dp/einf, "C(0) = 1/E0", rel=1.0e-14_dp)
        if (allocated(error)) return
        call check(error, real(m%compliance(1.0e12_dp/tau), dp), 1.0_dp/einf, "C(inf) = 1/Einf", rel=1.0e-10_dp)
        if (allocated(error)) return
        do k = -3, 3
            c = m%compliance(10.0_dp**k/tau)
            if (.not. aimag(c) < 0.0_dp) then
                call check(error, .false., "Im C(w) must be negative for w > 0"); return
            end if
        end do
        ! loss peak of E(w) = 1/C at w = Einf/(E0 tau) (notes, section 7)
        call check(error, aimag(1.0_dp/m%compliance(11.0_dp/tau)) > aimag(1.0_dp/m%compliance(11.0_dp/tau*1.05_dp)) &
                   .and. aimag(1.0_dp/m%compliance(11.0_dp/tau)) > aimag(1.0_dp/m%compliance(11.0_dp/tau/1.05_dp)), &
                   "loss modulus peaks at Einf/(E0 tau)")
    end subroutine test_compliance

    !> A one-term creep law is a one-term Maxwell relaxation law with rho = tau E0/Einf
    subroutine test_relaxation_creep(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: mc, mr
        real(dp) :: e0, w, worst
        integer :: k
        call paper_solid(11.0_dp, mc, error); if (allocated(error)) return
        e0 = einf/11.0_dp
        call new_relaxation(mr, e0, [einf - e0], [tau*e0/einf], 0.5_dp, error); if (allocated(error)) return
        worst = 0
        do k = -40, 40
            w = 10.0_dp**(k/10.0_dp)/tau
            worst = max(worst, abs(mc%compliance(w) - mr%compliance(w))*einf)
        end do
        call report("max |dC| Einf", worst)
        call check(error, worst <= 1.0e-14_dp, "creep and relaxation forms differ")
    end subroutine test_relaxation_creep

    !> An elastic solid has C = (1 - 0) / E at every frequency and no loss
    subroutine test_elastic(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        call new_elastic(m, 2.0e7_dp, 0.3_dp, error); if (allocated(error)) return
        call check(error, m%is_elastic(), "is_elastic"); if (allocated(error)) return
        call check(error, all(m%compliance([0.0_dp, 1.0_dp, 1.0e9_dp]) == cmplx(1.0_dp/2.0e7_dp, 0.0_dp, dp)), &
                   "elastic compliance depends on frequency")
    end subroutine test_elastic

    !> sum c_k >= 1/E0 would make the glassy modulus infinite or negative: refused
    !> One-term (standard linear) solid: tan(delta) peaks at (Einf - E0)/(2 sqrt(E0 Einf)) where
    !> omega = 1/sqrt(tau_creep tau_relax) = sqrt(Einf/E0)/tau; an elastic solid has none
    subroutine test_loss_peak(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        real(dp) :: w, td, ratio
        ratio = 11.0_dp
        call new_one_term(m, einf, ratio, tau, 0.5_dp, error); if (allocated(error)) return
        call m%loss_peak(w, td)
        call report("omega rel. error", abs(w - sqrt(ratio)/tau)/(sqrt(ratio)/tau))
        call report("tan delta rel. error", abs(td - (ratio - 1.0_dp)/(2.0_dp*sqrt(ratio)))/((ratio - 1.0_dp)/ &
                                                                                             (2.0_dp*sqrt(ratio))))
        call check(error, w, sqrt(ratio)/tau, "peak frequency", rel=1.0e-6_dp); if (allocated(error)) return
        call check(error, td, (ratio - 1.0_dp)/(2.0_dp*sqrt(ratio)), "peak tan(delta)", rel=1.0e-10_dp)
        if (allocated(error)) return
        call new_elastic(m, 1.0e7_dp, 0.5_dp, error); if (allocated(error)) return
        call m%loss_peak(w, td)
        call check(error, w == 0.0_dp .and. td == 0.0_dp, "an elastic solid has no loss peak")
    end subroutine test_loss_peak

    !> A relaxation and a creep series of 200 terms, times 1e-15..1e25 s (40 decades, 5 a decade),
    !> against the same sums in quadruple precision by complex division: C(w) within 1e-13 at
    !> w = 1e-30..1e30 rad/s (the real-arithmetic sums of material_compliance; measured 2e-16)
    subroutine test_long_series(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 200
        type(material_t) :: mr, mc
        real(dp) :: tau(n), e(n), c(n), w, worst
        complex(qp) :: s, cq
        integer :: j, k
        do j = 1, n
            tau(j) = 10.0_dp**(-15.0_dp + 40.0_dp*(j - 1)/(n - 1))
            e(j) = 1.0e6_dp*(1.0_dp + 0.5_dp*sin(0.1_dp*j))
        end do
        c = 1.0e-9_dp*e/sum(e)
        call new_relaxation(mr, 1.0e6_dp, e, tau, 0.5_dp, error); if (allocated(error)) return
        call new_creep(mc, 1.0e6_dp, c, tau, 0.5_dp, error); if (allocated(error)) return
        worst = 0.0_dp
        do k = -60, 60
            w = 10.0_dp**(k/2.0_dp)
            s = cmplx(1.0e6_qp, 0.0_qp, qp)
            do j = 1, n
                s = s + e(j)*cmplx(0.0_qp, w*real(tau(j), qp), qp)/cmplx(1.0_qp, w*real(tau(j), qp), qp)
            end do
            cq = 1.0_qp/s
            worst = max(worst, real(abs(mr%compliance(w) - cq)/abs(cq), dp))
            cq = cmplx(1.0_qp/mc%einf_pa, 0.0_qp, qp)
            do j = 1, n
                cq = cq + c(j)/cmplx(1.0_qp, w*real(tau(j), qp), qp)
            end do
            worst = max(worst, real(abs(mc%compliance(w) - cq)/abs(cq), dp))
            worst = max(worst, real(abs(mc%compliance(-w) - conjg(cq))/abs(cq), dp))
        end do
        call report("largest relative difference", worst)
        call check(error, worst <= 1.0e-13_dp, "C(w) of 200 terms differs from the quadruple-precision sum")
    end subroutine test_long_series

    !> The windowed sum of long series (material_compliance: the terms near |w t| = 1 one by one,
    !> the others through moments) against the term-by-term sums in quadruple precision: 200 terms
    !> with times spread evenly in log from 1e-12 to 1e200 s, and 256 terms, half of them so
    !> spread and half within 1e-4..1e4 s, given out of order and with a time twice; creep and
    !> relaxation forms; at w = 0, +-1e-215..1e15 rad/s every quarter decade (every term from far
    !> below its window to far above it) and at +-x/t_k for every time and x = 0.1, 0.3, 1, 10/3,
    !> 10 (the window's edges and middle). Re C and Im C each within 1e-14 of themselves
    !> (measured 1.7e-15, where the term-by-term sum in double precision is within 3.9e-15): the
    !> series leave out 2e-17, the rest is rounding
    subroutine test_windowed_sum(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp), parameter :: xs(5) = [0.1_dp, 0.3_dp, 1.0_dp, 10.0_dp/3.0_dp, 10.0_dp]
        type(material_t) :: mc, mr
        real(dp), allocatable :: t(:), c(:), e(:), w(:)
        real(dp) :: worst
        integer :: series, n, j, k
        worst = 0.0_dp
        do series = 1, 2
            n = merge(200, 256, series == 1)
            if (series == 1) then
                t = [(10.0_dp**(-12.0_dp + 212.0_dp*(j - 1)/(n - 1)), j = 1, n)]
            else
                ! every 37th of the merged list, modulo 256: out of order (37 is prime to 256)
                t = [(10.0_dp**(-12.0_dp + 212.0_dp*(j - 1)/127), j = 1, 128), &
                     (10.0_dp**(-4.0_dp + 8.0_dp*(j - 1)/127), j = 1, 128)]
                t = [(t(modulo(37*j, n) + 1), j = 0, n - 1)]
                t(5) = t(6)
            end if
            e = [(1.0e6_dp*(1.0_dp + 0.5_dp*sin(0.7_dp*j)), j = 1, n)]
            c = 1.0e-9_dp*e/sum(e)
            call new_relaxation(mr, 1.0e6_dp, e, t, 0.5_dp, error); if (allocated(error)) return
            call new_creep(mc, 1.0e6_dp, c, t, 0.5_dp, error); if (allocated(error)) return
            w = [0.0_dp, (10.0_dp**(k/4.0_dp), k = -860, 60), ((xs(k)/t(j), k = 1, size(xs)), j = 1, n)]
            w = [w, -w]
            do k = 1, size(w)
                call compare(mc%compliance(w(k)), term_by_term(.true., c, 1.0_dp/mc%einf_pa, w(k)))
                call compare(mr%compliance(w(k)), term_by_term(.false., e, 1.0e6_dp, w(k)))
            end do
        end do
        call report("largest relative difference of Re C or Im C", worst)
        call check(error, worst <= 1.0e-14_dp, "the windowed compliance differs from the term-by-term sum")
    contains
        subroutine compare(got, want)
            complex(dp), intent(in) :: got
            complex(qp), intent(in) :: want
            worst = max(worst, rel(real(got, dp), real(want, qp)), rel(aimag(got), aimag(want)))
        end subroutine compare
        ! (huge when a is not a number: max would pass a NaN over)
        real(dp) function rel(a, b)
            real(dp), intent(in) :: a
            real(qp), intent(in) :: b
            rel = 0.0_dp
            if (b /= 0.0_qp) then
                rel = real(abs(a - b)/abs(b), dp)
            else if (a /= 0.0_dp) then
                rel = huge(1.0_dp)
            end if
            if (.not. (rel <= huge(1.0_dp))) rel = huge(1.0_dp)
        end function rel
        ! creep: C = 1/Einf + sum c/(1 + i x); relaxation: C = 1/(E0 + sum e i x/(1 + i x)); x = w t
        complex(qp) function term_by_term(creep, coef, base, w) result(cq)
            logical, intent(in) :: creep
            real(dp), intent(in) :: coef(:), base, w
            complex(qp) :: s
            integer :: jt
            s = cmplx(base, 0.0_qp, qp)
            do jt = 1, size(coef)
                if (creep) then
                    s = s + coef(jt)/cmplx(1.0_qp, w*real(t(jt), qp), qp)
                else
                    s = s + coef(jt)*cmplx(0.0_qp, w*real(t(jt), qp), qp)/cmplx(1.0_qp, w*real(t(jt), qp), qp)
                end if
            end do
            cq = s
            if (.not. creep) cq = 1.0_qp/s
        end function term_by_term
    end subroutine test_windowed_sum

    !> A shift table holding WLF's values (C1 = 8.86, C2 = 101.6 K, Tref = 25 C at -50..100 C
    !> every 7.5 K) gives WLF's a_T at its temperatures (log10 a_T within 1e-12), against the
    !> reference 20 C and, moved, against 27.5 C; between them within 0.01 (PCHIP of a smooth law)
    !> and monotone
    subroutine test_table_is_wlf(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 21
        real(dp), parameter :: c1 = 8.86_dp, c2 = 101.6_dp
        real(dp) :: tc(n), la(n), worst, between, t, prev, lt
        integer :: k
        do k = 1, n
            tc(k) = -50.0_dp + 7.5_dp*(k - 1)
            la(k) = log10(shift_factor('wlf', tc(k), 25.0_dp, c1, c2, 0.0_dp))
        end do
        worst = 0.0_dp
        do k = 1, n
            worst = max(worst, abs(log10(shift_factor('table', tc(k), 25.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, tc, la)) - la(k)))
            worst = max(worst, abs(log10(shift_factor('table', tc(k), 32.5_dp, 0.0_dp, 0.0_dp, 0.0_dp, tc, la)) - &
                                   log10(shift_factor('wlf', tc(k), 32.5_dp, c1*c2/(c2 + 7.5_dp), c2 + 7.5_dp, 0.0_dp))))
        end do
        call report("largest |log10 a_T - WLF| at the table's points", worst)
        call check(error, worst <= 1.0e-12_dp, "the table's a_T differs from WLF at its points"); if (allocated(error)) return
        between = 0.0_dp; prev = huge(1.0_dp)
        do k = 0, 1500
            t = -50.0_dp + 0.1_dp*k
            lt = log10(shift_factor('table', t, 25.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, tc, la))
            between = max(between, abs(lt - log10(shift_factor('wlf', t, 25.0_dp, c1, c2, 0.0_dp))))
            if (.not. lt < prev) then
                call check(error, .false., "the table's log10 a_T is not decreasing at "//trim(adjustl(fmt(t)))); return
            end if
            prev = lt
        end do
        call report("largest |log10 a_T - WLF| between them", between)
        call check(error, between <= 0.2_dp, "the table strays from WLF between its points")
    contains
        function fmt(x) result(txt)
            real(dp), intent(in) :: x
            character(len=24) :: txt
            write (txt, '(g0)') x
        end function fmt
    end subroutine test_table_is_wlf

    !> pchip_value against scipy's PchipInterpolator (scipy 1.17) on a non-uniform table with a
    !> flat stretch (-1.1, -1.2): the same Fritsch-Butland slopes and end rule, within 1e-13
    subroutine test_pchip_scipy(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp), parameter :: x(9) = [-50.0_dp, -35.0_dp, -30.0_dp, -10.0_dp, 5.0_dp, 20.0_dp, 45.0_dp, 60.0_dp, &
                                       100.0_dp]
        real(dp), parameter :: y(9) = [9.1_dp, 6.8_dp, 5.2_dp, 3.0_dp, 1.4_dp, 0.0_dp, -1.1_dp, -1.2_dp, -3.9_dp]
        real(dp), parameter :: t(11) = [-50.0_dp, -42.3_dp, -30.0_dp, -31.7_dp, 0.4_dp, 20.0_dp, 33.3_dp, 59.9_dp, &
                                        61.0_dp, 99.99_dp, 100.0_dp]
        real(dp), parameter :: scipy(11) = [9.1_dp, 8.276017893691696_dp, 5.2_dp, 5.679448859583001_dp, &
            1.873414595714621_dp, 0.0_dp, -0.7461953986402002_dp, -1.1989289476244374_dp, -1.2125149349051538_dp, &
            -3.8988826552111324_dp, -3.8999999999999995_dp]
        real(dp) :: worst
        integer :: k
        worst = 0.0_dp
        do k = 1, size(t)
            worst = max(worst, abs(pchip_value(x, y, t(k)) - scipy(k)))
        end do
        worst = max(worst, abs(pchip_value([0.0_dp, 10.0_dp], [1.0_dp, -2.0_dp], 3.7_dp) + 0.11_dp))
        call report("largest difference", worst)
        call check(error, worst <= 1.0e-13_dp, "pchip_value differs from scipy's PchipInterpolator")
    end subroutine test_pchip_scipy

    subroutine test_creep_sum(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        call new_creep(m, 1.0e6_dp, [6.0e-7_dp, 5.0e-7_dp], [1.0e-3_dp, 1.0e-2_dp], 0.5_dp, error)
    end subroutine test_creep_sum

    subroutine test_bad_poisson(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        call new_one_term(m, einf, 11.0_dp, tau, 0.6_dp, error)
    end subroutine test_bad_poisson

    !> S(q d) against the layer's boundary-value problem solved numerically: plane strain for a
    !> mode exp(i q x) (q = 1, E = 1), the Navier equations' general solution
    !> U = (x1 + x2 z) e^z + (x3 + x4 z) e^-z, W = (-x1 + (kappa - z) x2) e^z + (x3 + (kappa + z) x4) e^-z,
    !> sigma_zz = lambda (U + W') + 2 mu W' = -1 and sigma_xz = mu (U' - W) = 0 at z = 0, and at
    !> z = d U = W = 0 (bonded) or W = sigma_xz = 0 (frictionless): S = W(0)/(2 (1 - nu^2))
    subroutine test_layer_bvp(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp), parameter :: ts(5) = [0.05_dp, 0.3_dp, 1.0_dp, 2.0_dp, 3.5_dp], nus(4) = [0.0_dp, 0.25_dp, &
                                                                                             0.4_dp, 0.45_dp]
        real(dp) :: worst, s_bvp, kappa
        integer :: it, iv, base
        worst = 0.0_dp
        do base = BASE_BONDED, BASE_FRICTIONLESS
            do iv = 1, size(nus)
                do it = 1, size(ts)
                    s_bvp = solve_layer(ts(it), nus(iv), base)
                    worst = max(worst, abs(layer_factor(ts(it), nus(iv), base)/s_bvp - 1.0_dp))
                end do
            end do
        end do
        call report("largest relative difference", worst)
        call check(error, worst <= 1.0e-12_dp, "S differs from the boundary-value problem")
    contains
        real(dp) function solve_layer(d, nu, base) result(s)
            real(dp), intent(in) :: d, nu
            integer, intent(in) :: base
            real(dp) :: a(4, 4), b(4, 1), lam, mu
            integer :: ipiv(4), info
            lam = nu/((1.0_dp + nu)*(1.0_dp - 2.0_dp*nu)); mu = 0.5_dp/(1.0_dp + nu); kappa = 3.0_dp - 4.0_dp*nu
            a(1, :) = lam*(cu(0.0_dp) + cwp(0.0_dp)) + 2.0_dp*mu*cwp(0.0_dp); b(1, 1) = -1.0_dp
            a(2, :) = mu*(cup(0.0_dp) - cw(0.0_dp)); b(2, 1) = 0.0_dp
            if (base == BASE_BONDED) then
                a(3, :) = cu(d)
            else
                a(3, :) = mu*(cup(d) - cw(d))
            end if
            a(4, :) = cw(d); b(3:4, 1) = 0.0_dp
            call dgesv(4, 1, a, 4, ipiv, b, 4, info)
            s = dot_product(cw(0.0_dp), b(:, 1))/(2.0_dp*(1.0_dp - nu**2))
            if (info /= 0) s = huge(1.0_dp)
        end function solve_layer
            function cu(z) result(c)
                real(dp), intent(in) :: z
                real(dp) :: c(4)
                c = [exp(z), z*exp(z), exp(-z), z*exp(-z)]
            end function cu
            function cup(z) result(c)
                real(dp), intent(in) :: z
                real(dp) :: c(4)
                c = [exp(z), (1.0_dp + z)*exp(z), -exp(-z), (1.0_dp - z)*exp(-z)]
            end function cup
            function cw(z) result(c)
                real(dp), intent(in) :: z
                real(dp) :: c(4)
                c = [-exp(z), (kappa - z)*exp(z), exp(-z), (kappa + z)*exp(-z)]
            end function cw
            function cwp(z) result(c)
                real(dp), intent(in) :: z
                real(dp) :: c(4)
                c = [-exp(z), (kappa - 1.0_dp - z)*exp(z), -exp(-z), (1.0_dp - kappa - z)*exp(-z)]
            end function cwp
    end subroutine test_layer_bvp

    !> The limits: q d >= 20 is the half-space to 1e-12; a thin bonded layer is the confined
    !> compression of its thickness, S/t -> (1 - 2 nu)/(2 (1 - nu)^2), and incompressible
    !> stiffens as (q d)^3: S = (2 t^3/3)(1 - 9 t^2/5 + 23 t^4/7 + ...) (the series of the closed
    !> form, 1e-4 .. 1e-1, where the closed form written directly cancels); a thin frictionless
    !> layer S/t -> 1/2;
    !> nu = 1/2 bonded is (sinh 2t - 2t)/(cosh 2t + 2t^2 + 1) (written directly where it does not cancel)
    subroutine test_layer_limits(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: t, worst
        integer :: base, k
        worst = 0.0_dp
        do base = BASE_BONDED, BASE_FRICTIONLESS
            do k = 0, 3
                t = 20.0_dp*10.0_dp**k
                worst = max(worst, abs(layer_factor(t, 0.3_dp, base) - 1.0_dp), abs(layer_factor(t, 0.5_dp, base) - 1.0_dp))
            end do
        end do
        call report("q d >= 20: largest |S - 1|", worst)
        call check(error, worst <= 1.0e-12_dp, "q d >= 20 is not the half-space"); if (allocated(error)) return
        t = 1.0e-7_dp
        call check(error, layer_factor(t, 0.3_dp, BASE_BONDED)/t, 0.4_dp/(2.0_dp*0.49_dp), "confined compression", &
                   rel=1.0e-6_dp)
        if (allocated(error)) return
        call check(error, layer_factor(t, 0.3_dp, BASE_FRICTIONLESS)/t, 0.5_dp, "free compression", rel=1.0e-6_dp)
        if (allocated(error)) return
        do k = 1, 4
            t = 10.0_dp**(-k)
            call check(error, layer_factor(t, 0.5_dp, BASE_BONDED)/(2.0_dp*t**3/3.0_dp), &
                       1.0_dp - 1.8_dp*t*t + 23.0_dp/7.0_dp*t**4, "incompressible: 2 t^3/3", rel=20.0_dp*t**6 + 1.0e-14_dp)
            if (allocated(error)) return
        end do
        do k = 1, 5
            t = 0.25_dp*k
            call check(error, layer_factor(t, 0.5_dp, BASE_BONDED), (sinh(2*t) - 2*t)/(cosh(2*t) + 2*t*t + 1), &
                       "nu = 1/2, bonded", rel=1.0e-13_dp)
            if (allocated(error)) return
        end do
    end subroutine test_layer_limits

end module test_veslide_material
