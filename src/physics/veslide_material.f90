!> Linear viscoelastic solid: Prony series of the creep compliance or of the relaxation modulus.
!>
!> Time dependence exp(+i w t). Creep form: J(t) = 1/E0 - sum_k c_k exp(-t/tau_k), so
!> C(w) = 1/Einf + sum_k c_k/(1 + i w tau_k), 1/Einf = 1/E0 - sum_k c_k. Relaxation form
!> (generalized Maxwell): E(w) = E0 + sum_j e_j i w rho_j/(1 + i w rho_j), C(w) = 1/E(w).
!> Im C(w) < 0 for w > 0 in both. An elastic solid is the case with no terms.
module veslide_material
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t, fatal_error
    implicit none
    private
    public :: material_t, new_elastic, new_one_term, new_creep, new_relaxation
    public :: MATERIAL_ELASTIC, MATERIAL_CREEP, MATERIAL_RELAXATION, material_model_names
    public :: shift_factor, shift_names, pchip_value, layer_factor, base_names, BASE_BONDED, BASE_FRICTIONLESS
    public :: coupling_beta

    !> Which series the terms of a material_t are
    integer, parameter :: MATERIAL_ELASTIC = 0, MATERIAL_CREEP = 1, MATERIAL_RELAXATION = 2
    !> The laws a material can be given by (the namelist's `&material model`); 'one_term' is a
    !> one-term creep series
    character(len=*), parameter :: material_model_names(4) = [character(len=10) :: 'elastic', 'one_term', &
                                                              'creep', 'relaxation']

    !> The laws of the temperature shift a_T (the namelist's `&material shift`)
    character(len=*), parameter :: shift_names(4) = [character(len=9) :: 'none', 'wlf', 'arrhenius', 'table']
    real(dp), parameter :: gas_constant = 8.314462618_dp     !! R [J/(mol K)] (CODATA 2018, exact)
    real(dp), parameter :: zero_celsius = 273.15_dp          !! [K]

    !> How a layer rests on its rigid base (the namelist's `&material base`)
    integer, parameter :: BASE_BONDED = 1, BASE_FRICTIONLESS = 2
    character(len=*), parameter :: base_names(2) = [character(len=12) :: 'bonded', 'frictionless']

    !> The windowed sum of a series longer than direct_terms (window_sums): the terms with
    !> win_lo <= |w t| < win_hi are summed one by one, those below and above through win_order
    !> terms of each of their series in w t or in 1/(w t) (window_sums: what they leave out); a
    !> frequency's window is read from a table by its bucket of |w| (the exponent and the top
    !> win_bits bits of the mantissa: a bucket's ends at most 1.25 apart). The choice, measured
    !> on the frequencies of the oblique 512^2 kernel (2^17) with the benchmark's spectrum over
    !> 12 decades: the window 0.1..10 with 8 terms took 54 ns a frequency for 200 terms, 0.2..5
    !> with 12 44 ns, 0.3..3.3 with 16 38 ns, 0.35..2.9 with 18 61 ns (past 16 the evaluation is
    !> no longer unrolled). Term by term costs 1.2 ns a term: 12 terms cost 19 ns either way, 8
    !> terms 13 ns term by term and 18 ns windowed, 20 terms 28 ns and 19 ns
    real(dp), parameter :: win_lo = 0.3_dp, win_hi = 1.0_dp/win_lo
    integer, parameter :: win_order = 16, win_bits = 2, direct_terms = 12

    type :: material_t
        integer :: form = MATERIAL_ELASTIC      !! which series the terms below are
        real(dp) :: e0_pa = 0.0_dp              !! relaxed (rubbery, w -> 0) modulus [Pa]
        real(dp) :: einf_pa = 0.0_dp            !! glassy (w -> infinity) modulus [Pa]
        real(dp) :: poisson = 0.0_dp            !! Poisson ratio [-]
        real(dp), allocatable :: coef(:)        !! c_k [1/Pa] (creep) or e_j [Pa] (relaxation)
        real(dp), allocatable :: time_s(:)      !! tau_k or rho_j [s]
        !> a layer of this thickness on a rigid base [m] (0: a half-space), and how it rests there
        real(dp) :: thickness_m = 0.0_dp
        integer :: base = BASE_BONDED
        !> the windowed sum of a series longer than direct_terms (set_window): the terms sorted
        !> by time, the moments of the terms below each one and above it, and per bucket of |w|
        !> the last term below the window and the first above it
        real(dp), allocatable, private :: sorted_coef(:), sorted_time(:)
        real(dp), allocatable, private :: below(:, :, :), above(:, :, :)
        integer, allocatable, private :: last_below(:), first_above(:)
        integer, private :: key_min = 0, key_max = -1
    contains
        procedure :: compliance => material_compliance
        procedure :: layer => material_layer
        procedure :: is_elastic => material_is_elastic
        procedure :: loss_peak_time => material_loss_peak_time
        procedure :: loss_peak => material_loss_peak
    end type material_t

contains

    !> The time-temperature shift factor a_T: a material at `t_c` behaves as the master curve at
    !> `t_ref_c` with every relaxation and retardation time multiplied by a_T,
    !> E*(w, T) = E*(a_T w, T_ref). 'wlf' (Williams, Landel & Ferry, J. Am. Chem. Soc. 77 (1955)
    !> 3701): log10 a_T = -c1 (T - T_ref)/(c2 + T - T_ref), c2 in kelvin; 'arrhenius':
    !> ln a_T = (E_a/R) (1/T - 1/T_ref), temperatures in kelvin; 'table': measured shift factors,
    !> log10 a_T = P(T) - P(T_ref) with P the monotone cubic (`pchip_value`) through the points
    !> (`table_c`, `table_log10`) (P(T_ref) = 0 when the table is relative to the reference, as a
    !> master curve's is); 'none': 1. The caller checks T - T_ref > -c2 (WLF), T > 0 K, and T and
    !> T_ref within the table (it is not extrapolated).
    pure real(dp) function shift_factor(shift, t_c, t_ref_c, c1, c2_k, activation_j_mol, table_c, table_log10) &
        result(a)
        character(len=*), intent(in) :: shift
        real(dp), intent(in) :: t_c, t_ref_c, c1, c2_k, activation_j_mol
        !> 'table': temperatures [C], strictly increasing, and log10 a_T there (2 or more)
        real(dp), intent(in), optional :: table_c(:), table_log10(:)
        select case (shift)
        case ('wlf')
            a = 10.0_dp**(-c1*(t_c - t_ref_c)/(c2_k + t_c - t_ref_c))
        case ('arrhenius')
            a = exp(activation_j_mol/gas_constant*(1.0_dp/(t_c + zero_celsius) - 1.0_dp/(t_ref_c + zero_celsius)))
        case ('table')
            a = 10.0_dp**(pchip_value(table_c, table_log10, t_c) - pchip_value(table_c, table_log10, t_ref_c))
        case default
            a = 1.0_dp
        end select
    end function shift_factor

    !> The piecewise cubic Hermite interpolant through (x_k, y_k) whose slopes keep monotone data
    !> monotone (PCHIP: Fritsch & Carlson, SIAM J. Numer. Anal. 17 (1980) 238; the slopes of
    !> Fritsch & Butland, SIAM J. Sci. Stat. Comput. 5 (1984) 300, as scipy's
    !> PchipInterpolator): at an interior point the weighted harmonic mean of the neighbouring
    !> secants, with w1 = 2 h_k + h_(k-1), w2 = h_k + 2 h_(k-1), or 0 where the secants differ
    !> in sign or one is 0; at either end the three-point estimate, set to 0 when its sign is not
    !> the first secant's and limited to 3 times that secant where the secants differ in sign;
    !> two points: the straight line. `x` strictly increasing (2 or more points); outside
    !> [x_1, x_n] the end cubics are extended (callers refuse such x).
    pure real(dp) function pchip_value(x, y, xi) result(yi)
        real(dp), intent(in) :: x(:), y(:), xi
        real(dp) :: h, m, d1, d2, s, c2, c3
        integer :: k, n
        n = size(x)
        k = 1
        do while (k < n - 1)
            if (xi < x(k + 1)) exit
            k = k + 1
        end do
        h = x(k + 1) - x(k); m = (y(k + 1) - y(k))/h
        d1 = pchip_slope(x, y, k); d2 = pchip_slope(x, y, k + 1)
        s = xi - x(k)
        c2 = (3.0_dp*m - 2.0_dp*d1 - d2)/h
        c3 = (d1 + d2 - 2.0_dp*m)/(h*h)
        yi = y(k) + s*(d1 + s*(c2 + s*c3))
    end function pchip_value

    !> The PCHIP slope at point k of (x, y) (see pchip_value)
    pure real(dp) function pchip_slope(x, y, k) result(d)
        real(dp), intent(in) :: x(:), y(:)
        integer, intent(in) :: k
        real(dp) :: h0, h1, m0, m1, w1, w2
        integer :: n
        n = size(x)
        if (n == 2) then
            d = (y(2) - y(1))/(x(2) - x(1)); return
        end if
        if (k == 1 .or. k == n) then
            if (k == 1) then
                h0 = x(2) - x(1); h1 = x(3) - x(2)
                m0 = (y(2) - y(1))/h0; m1 = (y(3) - y(2))/h1
            else
                h0 = x(n) - x(n - 1); h1 = x(n - 1) - x(n - 2)
                m0 = (y(n) - y(n - 1))/h0; m1 = (y(n - 1) - y(n - 2))/h1
            end if
            d = ((2.0_dp*h0 + h1)*m0 - h0*m1)/(h0 + h1)
            if (sign_of(d) /= sign_of(m0)) then
                d = 0.0_dp
            else if (sign_of(m0) /= sign_of(m1) .and. abs(d) > 3.0_dp*abs(m0)) then
                d = 3.0_dp*m0
            end if
            return
        end if
        h0 = x(k) - x(k - 1); h1 = x(k + 1) - x(k)
        m0 = (y(k) - y(k - 1))/h0; m1 = (y(k + 1) - y(k))/h1
        if (sign_of(m0) /= sign_of(m1) .or. m0 == 0.0_dp .or. m1 == 0.0_dp) then
            d = 0.0_dp
        else
            w1 = 2.0_dp*h1 + h0; w2 = h1 + 2.0_dp*h0
            d = (w1 + w2)/(w1/m0 + w2/m1)
        end if
    contains
        pure integer function sign_of(v) result(sg)
            real(dp), intent(in) :: v
            sg = 0
            if (v > 0.0_dp) sg = 1
            if (v < 0.0_dp) sg = -1
        end function sign_of
    end function pchip_slope

    !> The layer's factor S(q d) on the half-space's compliance of a surface mode |q| = `qn`
    !> (1 for a half-space). Derived for a mode exp(i q x) of normal traction on a layer
    !> 0 <= z <= d in plane strain (the 2-D problem of each mode) from the Navier equations, the
    !> surface free of shear, and at z = d either u = 0 (bonded) or u_z = 0 with no shear
    !> (frictionless); with t = q d and kappa = 3 - 4 nu,
    !>   bonded:        S = (kappa sinh 2t - 2t)/(kappa cosh 2t + 2t^2 + (1 + kappa^2)/2)
    !>   frictionless:  S = (cosh 2t - 1)/(sinh 2t + 2t)
    !> (docs/validation.md: the derivation's steps and checks). Limits: S -> 1 as t -> infinity;
    !> thin layers S -> t (1 - 2 nu)/(2 (1 - nu)^2) bonded (the confined compression of the layer,
    !> d (1+nu)(1-2nu)/(E(1-nu)) per unit pressure), S -> 2t^3/3 bonded and incompressible
    !> (stiffening as 1/(q d)^3), S -> t/2 frictionless (d (1-nu^2)/E). For nu = 1/2 and a bonded
    !> base S = (sinh 2t - 2t)/(cosh 2t + 2t^2 + 1). Evaluated without overflow (divided by
    !> cosh 2t) and, for small t, with sinh 2t - 2t from its series.
    elemental real(dp) function layer_factor(t, poisson, base) result(s)
        real(dp), intent(in) :: t, poisson
        integer, intent(in) :: base
        real(dp) :: kappa, x, sech, th, shx, x2
        integer :: k
        x = 2.0_dp*t
        if (x > 700.0_dp) then
            s = 1.0_dp; return
        end if
        sech = 1.0_dp/cosh(x); th = tanh(x)
        if (base == BASE_FRICTIONLESS) then
            ! (cosh x - 1)/(sinh x + x) = 2 sinh^2(t)/(sinh x + x)
            s = 2.0_dp*sinh(t)**2*sech/(th + x*sech)
            return
        end if
        kappa = 3.0_dp - 4.0_dp*poisson
        if (x < 0.5_dp) then              ! sinh x - x = x^3/3! + x^5/5! + ... (to x^17: 1e-17)
            x2 = x*x; shx = 0.0_dp
            do k = 17, 3, -2
                shx = (shx + 1.0_dp)*x2/real(k*(k - 1), dp)
            end do
            shx = shx*x
            ! kappa - 1 = 2 (1 - 2 nu), exact as nu -> 1/2
            s = (2.0_dp*(1.0_dp - 2.0_dp*poisson)*sinh(x) + shx)/(kappa*cosh(x) + 2.0_dp*t*t + &
                                                                 0.5_dp*(1.0_dp + kappa*kappa))
        else
            s = (kappa*th - x*sech)/(kappa + (2.0_dp*t*t + 0.5_dp*(1.0_dp + kappa*kappa))*sech)
        end if
    end function layer_factor

    !> The normal-tangential coupling of a half-space's surface, beta = (1 - 2 nu)/(2 (1 - nu))
    !> (Dundurs' beta of a rigid body against this solid): a shear traction t(q) on the surface
    !> moves it normally by -i beta (q.t)/|q| times the compliance of a pressure of mode q
    !> (docs/interface.md). 0 for an incompressible solid (nu = 1/2, exactly), 1/2 at nu = 0.
    elemental real(dp) function coupling_beta(poisson) result(beta)
        real(dp), intent(in) :: poisson
        beta = (1.0_dp - 2.0_dp*poisson)/(2.0_dp*(1.0_dp - poisson))
    end function coupling_beta

    !> The layer factor of this solid at |q| = `qn` [1/m] (1 for a half-space)
    elemental real(dp) function material_layer(self, qn) result(s)
        class(material_t), intent(in) :: self
        real(dp), intent(in) :: qn
        s = 1.0_dp
        if (self%thickness_m > 0.0_dp) s = layer_factor(qn*self%thickness_m, self%poisson, self%base)
    end function material_layer

    subroutine check_poisson(nu, error)
        real(dp), intent(in) :: nu
        type(error_t), allocatable, intent(out) :: error
        if (.not. (nu >= 0.0_dp .and. nu <= 0.5_dp)) &
            call fatal_error(error, "poisson must be in [0, 0.5]")
    end subroutine check_poisson

    !> Elastic solid of Young's modulus `young_pa`
    subroutine new_elastic(self, young_pa, poisson, error)
        type(material_t), intent(out) :: self
        real(dp), intent(in) :: young_pa, poisson
        type(error_t), allocatable, intent(out) :: error
        call check_poisson(poisson, error); if (allocated(error)) return
        if (.not. (young_pa > 0.0_dp .and. young_pa < huge(1.0_dp))) then
            call fatal_error(error, "young_pa must be positive and finite"); return
        end if
        self%form = MATERIAL_ELASTIC
        self%e0_pa = young_pa; self%einf_pa = young_pa; self%poisson = poisson
        allocate (self%coef(0), self%time_s(0))
    end subroutine new_elastic

    !> Creep Prony series: relaxed modulus E0 and terms c_k [1/Pa], tau_k [s]
    subroutine new_creep(self, e0_pa, c, tau_s, poisson, error)
        type(material_t), intent(out) :: self
        real(dp), intent(in) :: e0_pa, c(:), tau_s(:), poisson
        type(error_t), allocatable, intent(out) :: error
        call check_poisson(poisson, error); if (allocated(error)) return
        if (size(c) /= size(tau_s) .or. size(c) < 1) then
            call fatal_error(error, "creep series needs as many c_k as tau_k, at least one"); return
        end if
        if (.not. (e0_pa > 0.0_dp) .or. any(.not. (c > 0.0_dp)) .or. any(.not. (tau_s > 0.0_dp))) then
            call fatal_error(error, "E0, c_k and tau_k must all be positive"); return
        end if
        if (.not. (sum(c) < 1.0_dp/e0_pa)) then
            call fatal_error(error, "sum of c_k must be below 1/E0 (glassy modulus Einf > E0 > 0)"); return
        end if
        self%form = MATERIAL_CREEP
        self%e0_pa = e0_pa; self%einf_pa = 1.0_dp/(1.0_dp/e0_pa - sum(c)); self%poisson = poisson
        self%coef = c; self%time_s = tau_s
        call set_window(self)
    end subroutine new_creep

    !> The paper's one-term solid: glassy modulus, ratio Einf/E0 > 1, retardation time tau
    subroutine new_one_term(self, einf_pa, ratio, tau_s, poisson, error)
        type(material_t), intent(out) :: self
        real(dp), intent(in) :: einf_pa, ratio, tau_s, poisson
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: e0
        if (.not. (einf_pa > 0.0_dp)) then
            call fatal_error(error, "einf_pa must be positive"); return
        end if
        if (.not. (ratio > 1.0_dp)) then
            call fatal_error(error, "ratio Einf/E0 must be > 1"); return
        end if
        e0 = einf_pa/ratio
        call new_creep(self, e0, [1.0_dp/e0 - 1.0_dp/einf_pa], [tau_s], poisson, error)
        if (allocated(error)) return
        self%einf_pa = einf_pa     ! exact, not through 1/(1/E0 - c)
    end subroutine new_one_term

    !> Relaxation (generalized Maxwell) Prony series: E(t) = E0 + sum_j e_j exp(-t/rho_j)
    subroutine new_relaxation(self, e0_pa, e, rho_s, poisson, error)
        type(material_t), intent(out) :: self
        real(dp), intent(in) :: e0_pa, e(:), rho_s(:), poisson
        type(error_t), allocatable, intent(out) :: error
        call check_poisson(poisson, error); if (allocated(error)) return
        if (size(e) /= size(rho_s) .or. size(e) < 1) then
            call fatal_error(error, "relaxation series needs as many e_j as rho_j, at least one"); return
        end if
        if (.not. (e0_pa > 0.0_dp) .or. any(.not. (e > 0.0_dp)) .or. any(.not. (rho_s > 0.0_dp))) then
            call fatal_error(error, "E0, e_j and rho_j must all be positive"); return
        end if
        self%form = MATERIAL_RELAXATION
        self%e0_pa = e0_pa; self%einf_pa = e0_pa + sum(e); self%poisson = poisson
        self%coef = e; self%time_s = rho_s
        call set_window(self)
    end subroutine new_relaxation

    !> Complex compliance C(w) = 1/E(w) [1/Pa] at angular frequency w [rad/s]. Each term in real
    !> arithmetic, with x = w t and d = 1/(1 + x^2): i x/(1 + i x) = x^2 d + i x d (relaxation),
    !> 1/(1 + i x) = d - i x d (creep). A series of up to direct_terms (12) terms is summed term by
    !> term, x held within +-1e100 (which changes no term by more than 1e-200 of itself) so that
    !> x^2 stays finite for times up to the input's 1e200 s. A longer one sums term by term only
    !> the terms of its window, 0.3 <= |x| < 3.3 (a little wider, to its bucket of |w|), and the
    !> terms below and above it through the moments of their series (window_sums), within 2e-17
    !> of each sum: a frequency costs about what 30 terms do one by one, more only as the terms
    !> are denser in its window (the benchmark's spectrum over 12 decades: 20 terms 19 ns, 200
    !> 38 ns, 256 46 ns; one by one 28, 253 and 323 ns). The kernel evaluates this once per mode
    !> when sliding obliquely (docs/benchmarks.md)
    elemental complex(dp) function material_compliance(self, w) result(c)
        class(material_t), intent(in) :: self
        real(dp), intent(in) :: w
        real(dp), parameter :: x_max = 1.0e100_dp
        real(dp) :: x, d, re, im
        integer :: k
        select case (self%form)
        case (MATERIAL_CREEP)
            if (allocated(self%sorted_time)) then
                call window_sums(self, w, re, im)
            else
                re = 0.0_dp; im = 0.0_dp
                !$omp simd reduction(+:re, im) private(x, d)
                do k = 1, size(self%coef)
                    x = max(-x_max, min(x_max, w*self%time_s(k)))
                    d = 1.0_dp/(1.0_dp + x*x)
                    re = re + self%coef(k)*d
                    im = im + self%coef(k)*(x*d)
                end do
            end if
            c = cmplx(1.0_dp/self%einf_pa + re, -im, dp)
        case (MATERIAL_RELAXATION)
            if (allocated(self%sorted_time)) then
                call window_sums(self, w, re, im)
            else
                re = 0.0_dp; im = 0.0_dp
                !$omp simd reduction(+:re, im) private(x, d)
                do k = 1, size(self%coef)
                    x = max(-x_max, min(x_max, w*self%time_s(k)))
                    d = 1.0_dp/(1.0_dp + x*x)
                    re = re + self%coef(k)*(x*x*d)
                    im = im + self%coef(k)*(x*d)
                end do
            end if
            c = 1.0_dp/cmplx(self%e0_pa + re, im, dp)
        case default
            c = cmplx(1.0_dp/self%e0_pa, 0.0_dp, dp)
        end select
    end function material_compliance

    !> The sums re, im of material_compliance's terms (creep: sum c d, sum c x d; relaxation:
    !> sum e x^2 d, sum e x d) by the window of w: with the terms sorted by time t_1 <= .. <= t_n,
    !> those up to `last` have |x| < 0.3, those from `first` on |x| >= 1/0.3 (set_window), and
    !> the ones between are summed term by term. Below, with y = w t_last, s = y^2 and the
    !> moments P_m = sum_(k<=last) c_k (t_k/t_last)^m,
    !>   1/(1 + x^2) = sum_i (-1)^i x^(2i):     sum c d     = sum_i (-1)^i P_2i s^i
    !>   x/(1 + x^2) = sum_i (-1)^i x^(2i+1):   sum c x d   = y sum_i (-1)^i P_(2i+1) s^i
    !>   x^2/(1 + x^2) = sum_i (-1)^i x^(2i+2): sum c x^2 d = s sum_i (-1)^i P_(2i+2) s^i
    !> and above, the same in z = 1/(w t_first) and Q_m = sum_(k>=first) c_k (t_first/t_k)^m
    !> (1/(1 + x^2) = z^2/(1 + z^2), x/(1 + x^2) = z/(1 + z^2), x^2/(1 + x^2) = 1/(1 + z^2)).
    !> The moments hold ratios of times at most 1: no overflow however far apart the times are
    !> (w t_first may overflow: z = 0, the limit). Bound: each series alternates with terms
    !> falling by x^2 < 0.09 (or z^2), so cut after win_order = 16 terms it leaves out less than
    !> x^32 of the term's sum, x^32 (1 + x^2) <= 0.3^32 1.09 = 2.0e-17 of its part of re or im;
    !> and all the parts of re have one sign, as have those of im (that of w), so re and im are
    !> each within 2e-17 of themselves, and C within about as much of |C|: below their rounding
    pure subroutine window_sums(self, w, re, im)
        class(material_t), intent(in) :: self
        real(dp), intent(in) :: w
        real(dp), intent(out) :: re, im
        real(dp) :: x, d, y, s, part(2)
        integer :: key, last, first, k, n
        n = size(self%sorted_time)
        key = window_key(w)
        if (key < self%key_min) then
            last = n; first = n + 1
        else if (key > self%key_max) then
            last = 0; first = 1
        else
            last = self%last_below(key); first = self%first_above(key)
        end if
        re = 0.0_dp; im = 0.0_dp
        if (self%form == MATERIAL_CREEP) then
            !$omp simd reduction(+:re, im) private(x, d)
            do k = last + 1, first - 1
                x = w*self%sorted_time(k)
                d = 1.0_dp/(1.0_dp + x*x)
                re = re + self%sorted_coef(k)*d
                im = im + self%sorted_coef(k)*(x*d)
            end do
        else
            !$omp simd reduction(+:re, im) private(x, d)
            do k = last + 1, first - 1
                x = w*self%sorted_time(k)
                d = 1.0_dp/(1.0_dp + x*x)
                re = re + self%sorted_coef(k)*(x*x*d)
                im = im + self%sorted_coef(k)*(x*d)
            end do
        end if
        if (last > 0) then
            y = w*self%sorted_time(last); s = y*y
            part = series(self%below(:, :, last), s)
            if (self%form == MATERIAL_RELAXATION) part(1) = part(1)*s
            re = re + part(1)
            im = im + y*part(2)
        end if
        if (first <= n) then
            y = 1.0_dp/(w*self%sorted_time(first)); s = y*y
            part = series(self%above(:, :, first), s)
            if (self%form == MATERIAL_CREEP) part(1) = part(1)*s
            re = re + part(1)
            im = im + y*part(2)
        end if
    contains
        ! sum_i p_i s^(i-1) for the real and the imaginary series side by side, by Estrin's
        ! scheme (the terms paired, p_2i-1 + p_2i s, then the pairs in s^2, and so on): a chain
        ! of log2(win_order) steps where Horner's has win_order, which bounded the time
        pure function series(p, s) result(v)
            real(dp), intent(in) :: p(2, win_order), s
            real(dp) :: v(2), a(2, win_order), sk
            integer :: i, m
            a = p; sk = s; m = win_order
            do while (m > 1)
                do i = 1, m/2
                    a(:, i) = a(:, 2*i - 1) + a(:, 2*i)*sk
                end do
                if (modulo(m, 2) == 1) a(:, m/2 + 1) = a(:, m)
                m = (m + 1)/2; sk = sk*sk
            end do
            v = a(:, 1)
        end function series
    end subroutine window_sums

    !> The bucket of |w| of the windowed sum: the exponent and top win_bits bits of the mantissa
    !> of binary64 |w| as one integer, which grows with |w| (0 for w = 0); the bucket k holds
    !> [window_bound(k), window_bound(k + 1))
    elemental integer function window_key(w) result(key)
        real(dp), intent(in) :: w
        key = int(shiftr(transfer(abs(w), 0_i8), digits(w) - 1 - win_bits))
    end function window_key

    elemental real(dp) function window_bound(key) result(w)
        integer, intent(in) :: key
        w = transfer(shiftl(int(key, i8), digits(w) - 1 - win_bits), w)
    end function window_bound

    !> The windowed sum's tables for a series longer than direct_terms (window_sums): the terms
    !> sorted by time (stable: coef and time_s keep the input's order), the moments of each
    !> term's prefix and suffix by recurrence, P_m(j) = P_m(j-1) (t_(j-1)/t_j)^m + c_j and
    !> Q_m(j) = Q_m(j+1) (t_j/t_(j+1))^m + c_j, signed and ordered as window_sums reads them,
    !> and per bucket of |w| the last term with |x| < 0.3 and the first with |x| >= 1/0.3 over
    !> the whole bucket (below key_min every term is below, above key_max every one above)
    pure subroutine set_window(self)
        type(material_t), intent(inout) :: self
        integer :: n, j, i, k, last, first, order(size(self%time_s))
        real(dp) :: p(0:2*win_order), r, rm, sg, lo, hi
        logical :: creep
        n = size(self%time_s)
        if (n <= direct_terms) return
        creep = self%form == MATERIAL_CREEP
        order = [(j, j = 1, n)]
        do j = 2, n
            k = order(j); i = j - 1
            do while (i >= 1)
                if (self%time_s(order(i)) <= self%time_s(k)) exit
                order(i + 1) = order(i); i = i - 1
            end do
            order(i + 1) = k
        end do
        self%sorted_time = self%time_s(order); self%sorted_coef = self%coef(order)
        associate (t => self%sorted_time, c => self%sorted_coef)
            allocate (self%below(2, win_order, n), self%above(2, win_order, n))
            p = 0.0_dp
            do j = 1, n
                r = 1.0_dp; if (j > 1) r = t(j - 1)/t(j)
                rm = 1.0_dp
                do i = 0, 2*win_order
                    p(i) = p(i)*rm + c(j); rm = rm*r
                end do
                do i = 0, win_order - 1
                    sg = real(1 - 2*modulo(i, 2), dp)
                    self%below(1, i + 1, j) = sg*merge(p(2*i), p(2*i + 2), creep)
                    self%below(2, i + 1, j) = sg*p(2*i + 1)
                end do
            end do
            p = 0.0_dp
            do j = n, 1, -1
                r = 1.0_dp; if (j < n) r = t(j)/t(j + 1)
                rm = 1.0_dp
                do i = 0, 2*win_order
                    p(i) = p(i)*rm + c(j); rm = rm*r
                end do
                do i = 0, win_order - 1
                    sg = real(1 - 2*modulo(i, 2), dp)
                    self%above(1, i + 1, j) = sg*merge(p(2*i + 2), p(2*i), creep)
                    self%above(2, i + 1, j) = sg*p(2*i + 1)
                end do
            end do
            self%key_min = window_key(win_lo/t(n)); self%key_max = window_key(win_hi/t(1))
            allocate (self%last_below(self%key_min:self%key_max))
            allocate (self%first_above(self%key_min:self%key_max))
            last = n; first = n + 1
            do k = self%key_min, self%key_max
                lo = window_bound(k); hi = window_bound(k + 1)
                do while (last > 0)
                    if (hi*t(last) <= win_lo) exit
                    last = last - 1
                end do
                do while (first > 1)
                    if (lo*t(first - 1) < win_hi) exit
                    first = first - 1
                end do
                self%last_below(k) = last; self%first_above(k) = first
            end do
        end associate
    end subroutine set_window

    logical function material_is_elastic(self) result(yes)
        class(material_t), intent(in) :: self
        yes = self%form == MATERIAL_ELASTIC
    end function material_is_elastic

    !> The time whose inverse is the frequency of the loss peak of a one-term solid, as used in
    !> dimensionless speeds v*tau/L0: the (first) retardation time tau for creep input, the
    !> relaxation time rho for relaxation input, 0 for an elastic solid.
    real(dp) function material_loss_peak_time(self) result(t)
        class(material_t), intent(in) :: self
        t = 0.0_dp
        if (size(self%time_s) > 0) t = self%time_s(1)
    end function material_loss_peak_time

    !> The peak of the loss tangent tan(delta) = Im E/Re E = -Im C/Re C over frequency, and the
    !> angular frequency where it lies [rad/s] (0, 0 for an elastic solid): a scan over log(w)
    !> spanning every Prony time by two decades either side (at least 20 points a decade),
    !> refined by golden sections
    subroutine material_loss_peak(self, omega, tan_delta)
        class(material_t), intent(in) :: self
        real(dp), intent(out) :: omega, tan_delta
        integer :: nscan
        real(dp) :: lo, hi, a, b, x1, x2, f1, f2, best, t
        real(dp), parameter :: gr = 0.6180339887498949_dp
        integer :: k, kbest
        omega = 0.0_dp; tan_delta = 0.0_dp
        if (self%is_elastic() .or. size(self%time_s) == 0) return
        lo = log(0.01_dp/maxval(self%time_s)); hi = log(100.0_dp/minval(self%time_s))
        nscan = max(400, ceiling(20.0_dp*(hi - lo)/log(10.0_dp)))
        best = -1.0_dp; kbest = 0
        do k = 0, nscan
            t = tan_at(lo + (hi - lo)*k/nscan)
            if (t > best) then
                best = t; kbest = k
            end if
        end do
        a = lo + (hi - lo)*max(kbest - 1, 0)/nscan; b = lo + (hi - lo)*min(kbest + 1, nscan)/nscan
        x1 = b - gr*(b - a); x2 = a + gr*(b - a); f1 = tan_at(x1); f2 = tan_at(x2)
        do k = 1, 60
            if (f1 > f2) then
                b = x2; x2 = x1; f2 = f1; x1 = b - gr*(b - a); f1 = tan_at(x1)
            else
                a = x1; x1 = x2; f1 = f2; x2 = a + gr*(b - a); f2 = tan_at(x2)
            end if
        end do
        omega = exp(0.5_dp*(a + b)); tan_delta = tan_at(0.5_dp*(a + b))
    contains
        real(dp) function tan_at(lw) result(td)
            real(dp), intent(in) :: lw
            complex(dp) :: c
            c = self%compliance(exp(lw))
            td = -aimag(c)/real(c, dp)
        end function tan_at
    end subroutine material_loss_peak

end module veslide_material
