!> Anisotropy tensors, the stretch-and-rotation decomposition, patches and percolation
module test_veslide_anisotropy
    use veslide_kinds, only: dp, pi, i8
    use veslide_error, only: error_t
    use veslide_grid, only: grid_t, new_grid
    use veslide_fftw, only: fft2d_t
    use veslide_spectrum, only: slope_tensor
    use veslide_anisotropy, only: tensor_axes, decompose, compose, m2_of_theta
    use veslide_patches, only: patch_stats_t, contact_patches, percolates, patch_changes, cell_set_t, cell_set
    use veslide_strings, only: str
    use testsuite, only: unittest_t, new_unittest, check, report
    implicit none
    private
    public :: collect_anisotropy

contains

    subroutine collect_anisotropy(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("rotated-field-rotated-tensor", test_rotation), &
            new_unittest("m2-polar-extremes", test_m2), &
            new_unittest("synthetic-decomposition-recovered", test_recover), &
            new_unittest("isotropic-and-degenerate-rule", test_degenerate), &
            new_unittest("patches-across-periodic-boundary", test_patches), &
            new_unittest("patch-orientation", test_patch_orientation), &
            new_unittest("stripe-percolation", test_percolation), &
            new_unittest("patches-made-and-lost", test_patch_changes), &
            new_unittest("patches-bistable", test_patches_bistable) &
            ]
    end subroutine collect_anisotropy

    !> An anisotropic Gaussian bump and the same bump turned by beta: the slope tensor turns by beta
    subroutine test_rotation(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 256
        type(fft2d_t) :: fft
        real(dp) :: h(n, n), m0(2, 2), mb(2, 2), r(2, 2), beta, worst
        integer :: k
        type(grid_t) :: grid
        call new_grid(grid, n, n, 1.0_dp, 1.0_dp, error); if (allocated(error)) return
        call fft%init(n, n, error, planner='estimate'); if (allocated(error)) return
        call bump(0.0_dp, h); call slope_tensor(grid, fft, h, m0)
        worst = 0
        do k = 1, 5
            beta = k*pi/7
            call bump(beta, h); call slope_tensor(grid, fft, h, mb)
            r = reshape([cos(beta), sin(beta), -sin(beta), cos(beta)], [2, 2])
            worst = max(worst, maxval(abs(mb - matmul(r, matmul(m0, transpose(r)))))/maxval(abs(m0)))
        end do
        call report("max rel. difference", worst)
        ! the bump is resolved spectrally (width 20 cells): only its tail beyond the cell remains
        call check(error, worst <= 1.0e-9_dp, "tensor did not rotate with the field")
    contains
        subroutine bump(b, f)
            real(dp), intent(in) :: b
            real(dp), intent(out) :: f(:, :)
            integer :: i, j
            real(dp) :: x, y, u, v
            do j = 1, n
                do i = 1, n
                    x = (i - 1 - n/2)/real(n, dp); y = (j - 1 - n/2)/real(n, dp)
                    u = cos(b)*x + sin(b)*y; v = -sin(b)*x + cos(b)*y
                    f(i, j) = exp(-(u/0.08_dp)**2 - (v/0.03_dp)**2)
                end do
            end do
        end subroutine bump
    end subroutine test_rotation

    subroutine test_m2(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: m(2, 2), l1, l2, th, t(3600), m2(3600)
        integer :: k
        m = reshape([3.0_dp, 1.2_dp, 1.2_dp, 1.0_dp], [2, 2])
        call tensor_axes(m, l1, l2, th)
        t = [(k*pi/3600, k = 1, 3600)]
        m2 = m2_of_theta(m, t)
        call check(error, maxval(m2), l1, "max of m2 = lambda_max", rel=1.0e-6_dp); if (allocated(error)) return
        call check(error, minval(m2), l2, "min of m2 = lambda_min", rel=1.0e-6_dp); if (allocated(error)) return
        call check(error, abs(t(maxloc(m2, 1)) - th) <= pi/3600, "theta_max")
    end subroutine test_m2

    !> compose(M, sigma1, sigma2, phi) then decompose gives sigma1, sigma2, phi back for
    !> |phi| < pi/4; beyond, the smallest-rotation rule returns the other pairing, which must
    !> still reproduce Md exactly
    subroutine test_recover(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: m(2, 2), md(2, 2), s1, s2, ph, worst, worst_md, alpha, rs(2, 2), phi
        integer :: ia, ip
        worst = 0; worst_md = 0
        do ia = 0, 7
            alpha = ia*pi/8
            rs = reshape([cos(alpha), sin(alpha), -sin(alpha), cos(alpha)], [2, 2])
            m = matmul(rs, matmul(reshape([2.0_dp, 0.0_dp, 0.0_dp, 0.7_dp], [2, 2]), transpose(rs)))
            do ip = -6, 6
                phi = ip*pi/14
                md = compose(m, 0.8_dp, 1.3_dp, phi)
                call decompose(m, md, 1.0e-9_dp, s1, s2, ph)
                if (abs(phi) < pi/4) worst = max(worst, abs(s1 - 0.8_dp), abs(s2 - 1.3_dp), abs(ph - phi))
                worst_md = max(worst_md, maxval(abs(compose(m, s1, s2, ph) - md)))
            end do
        end do
        call report("worst recovered", worst); call report("worst re-composed", worst_md)
        call check(error, worst <= 1.0e-12_dp, "decomposition not recovered"); if (allocated(error)) return
        call check(error, worst_md <= 1.0e-12_dp, "decomposition does not reproduce Md")
    end subroutine test_recover

    !> Isotropic M: phi = 0 and sigma from the eigenvalues of Md; eigenvalue crossing: the pairing
    !> with the smaller rotation is taken (here a stretch that makes the minor axis the major one)
    subroutine test_degenerate(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: m(2, 2), md(2, 2), s1, s2, ph
        m = reshape([1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 2])
        md = reshape([0.4_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 2])
        call decompose(m, md, 1.0e-6_dp, s1, s2, ph)
        call check(error, ph == 0.0_dp .and. abs(s1 - 1.0_dp) < 1e-15_dp .and. abs(s2 - 0.4_dp) < 1e-15_dp, &
                   "isotropic rule"); if (allocated(error)) return
        ! M major along x (2 vs 1); Md = diag(2*0.3, 1*1.5): Md's major axis is y. Pairing major-major
        ! would need phi = 90 deg; the rule keeps phi = 0 and reports sigma1 = 0.3, sigma2 = 1.5
        m = reshape([2.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 2])
        md = reshape([0.6_dp, 0.0_dp, 0.0_dp, 1.5_dp], [2, 2])
        call decompose(m, md, 1.0e-6_dp, s1, s2, ph)
        call check(error, abs(ph) < 1e-15_dp .and. abs(s1 - 0.3_dp) < 1e-15_dp .and. abs(s2 - 1.5_dp) < 1e-15_dp, &
                   "eigenvalue crossing rule")
    end subroutine test_degenerate

    subroutine test_patches(error)
        type(error_t), allocatable, intent(out) :: error
        logical :: mask(16, 16)
        type(patch_stats_t) :: st
        mask = .false.
        mask([1, 2, 16], 1) = .true.; mask([1, 16], 16) = .true.     ! one patch over the corner
        mask(8:9, 8:9) = .true.                                       ! a second, inside
        call contact_patches(mask, 1.0_dp, 1.0_dp, st)
        call check(error, st%count, 2, "patch count"); if (allocated(error)) return
        call check(error, st%mean_area_fraction, 9.0_dp/2/256, "mean patch area", rel=1.0e-15_dp)
    end subroutine test_patches

    !> A bar of 12 x 2 cells along x and one along y: gamma = (4/12 ... ), axes 0 and pi/2
    subroutine test_patch_orientation(error)
        type(error_t), allocatable, intent(out) :: error
        logical :: mask(32, 32)
        type(patch_stats_t) :: st
        mask = .false.; mask(30:32, 5) = .true.; mask(1:9, 5) = .true.   ! 12 cells along x, across the edge
        call contact_patches(mask, 1.0_dp, 1.0_dp, st)
        call report("gamma", st%gamma); call report("theta", st%theta)
        ! gyration of a 12 x 1 bar of unit cells: (144/12) along, 1/12 across
        call check(error, st%gamma, (1.0_dp/12)/(144.0_dp/12), "elongation", rel=1.0e-12_dp); if (allocated(error)) return
        call check(error, abs(st%theta) < 1.0e-12_dp, "axis along x"); if (allocated(error)) return
        mask = transpose(mask)
        call contact_patches(mask, 1.0_dp, 1.0_dp, st)
        call check(error, st%theta, pi/2, "axis along y", abs=1.0e-12_dp)
    end subroutine test_patch_orientation

    subroutine test_percolation(error)
        type(error_t), allocatable, intent(out) :: error
        logical :: gap(32, 32)
        gap = .true.
        gap(:, 10) = .false.; gap(:, 20) = .false.     ! contact lines along x: channels along x only
        call check(error, percolates(gap, 1), "percolates along x"); if (allocated(error)) return
        call check(error, .not. percolates(gap, 2), "does not percolate along y"); if (allocated(error)) return
        gap(5, :) = .false.                            ! and a line along y closes the channels
        call check(error, .not. percolates(gap, 1) .and. .not. percolates(gap, 2), "closed cells")
    end subroutine test_percolation

    !> Between two masks: a patch over the corner (one patch through both periodic edges) that
    !> shrinks stays (neither made nor lost); one that vanishes is lost; a new one (3 cells, across
    !> the x edge) is made; a patch that splits in two, each part holding an old cell, is neither
    !> made nor lost; full contact after partial is neither
    subroutine test_patch_changes(error)
        type(error_t), allocatable, intent(out) :: error
        logical :: a(16, 12), b(16, 12)
        integer :: made, lost
        integer(i8) :: cm, cl
        a = .false.; b = .false.
        a([1, 2, 16], 1) = .true.; a([1, 16], 12) = .true.      ! the corner patch, 5 cells
        b(16, 12) = .true.                                       ! ... shrunk to 1
        a(8:9, 6:7) = .true.                                     ! lost, 4 cells
        b(16, 6) = .true.; b(1:2, 6) = .true.                    ! made, 3 cells across the x edge
        a(4:8, 10) = .true.; b([4, 8], 10) = .true.              ! split, each part an old cell
        call patch_changes(a, b, made, lost, cm, cl)
        call check(error, made == 1 .and. lost == 1 .and. cm == 3 .and. cl == 4, "made "//str(made)// &
                   " ("//str(int(cm))//" cells), lost "//str(lost)//" ("//str(int(cl))//" cells): expected 1 (3), 1 (4)")
        if (allocated(error)) return
        call patch_changes(b, a, made, lost, cm, cl)
        call check(error, made == 1 .and. lost == 1 .and. cm == 4 .and. cl == 3, "reversed: made and lost swap")
        if (allocated(error)) return
        b = .true.
        call patch_changes(a, b, made, lost, cm, cl)
        call check(error, made == 0 .and. lost == 0 .and. cm == 0 .and. cl == 0, "full contact: one patch, old cells")
        if (allocated(error)) return
        call patch_changes(a, .not. b, made, lost, cm, cl)
        call check(error, made == 0 .and. lost == 3 .and. cl == count(a), "no contact: every patch lost")
    end subroutine test_patch_changes

    !> A set of cells kept as runs holds exactly the mask's cells (runs crossing rows, one at the
    !> last cell); the patches made and lost between two states that earlier states at the same
    !> controls held the other way: none where those states are the two themselves, both where
    !> the after control held the before state, and each alone as the sets decide
    subroutine test_patches_bistable(error)
        type(error_t), allocatable, intent(out) :: error
        logical :: a(16, 12), b(16, 12), m(16, 12), e(16, 12)
        type(cell_set_t) :: s
        type(cell_set_t), allocatable :: none(:)
        integer :: made, lost, nb, r
        integer(i8) :: cm, cl, c
        a = .false.; b = .false.
        a([1, 2, 16], 1) = .true.; a([1, 16], 12) = .true.      ! the corner patch: kept
        b(16, 12) = .true.
        a(8:9, 6:7) = .true.                                     ! lost, 4 cells
        b(16, 6) = .true.; b(1:2, 6) = .true.                    ! made, 3 cells across the x edge
        ! the runs: expanded again they are the mask
        m = a .or. b; m(1, 7) = .true.                          ! (a run from row 6 into row 7)
        s = cell_set(m)
        e = .false.
        do r = 1, size(s%runs, 2)
            do c = s%runs(1, r), s%runs(1, r) + s%runs(2, r) - 1
                e(int(modulo(c - 1, 16_i8)) + 1, int((c - 1)/16) + 1) = .true.
            end do
        end do
        call check(error, all(e .eqv. m) .and. size(s%runs, 2) == 8, "the runs of a set are not its cells ("// &
                   str(size(s%runs, 2))//" runs, expected 8)")
        if (allocated(error)) return
        ! the states themselves at their controls: nothing is bistable
        call patch_changes(a, b, made, lost, cm, cl, at_before=[cell_set(a)], at_after=[cell_set(b)], bistable=nb)
        call check(error, made == 1 .and. lost == 1 .and. nb == 0, "the two states themselves: "//str(nb)//" bistable")
        if (allocated(error)) return
        ! the after control held the before state earlier: both patches are bistable
        allocate (none(0))     ! (a variable: gfortran 12 passes a literal empty list as absent)
        call patch_changes(a, b, made, lost, cm, cl, at_before=none, at_after=[cell_set(a)], bistable=nb)
        call check(error, nb == 2, "after's control held the before state: "//str(nb)//" bistable, expected 2")
        if (allocated(error)) return
        ! the before control held nothing: the lost patch only; held the made one's cell: it only
        call patch_changes(a, b, made, lost, cm, cl, at_before=[cell_set(.not. (a .or. b))], &
                           at_after=[cell_set(b)], bistable=nb)
        call check(error, nb == 1, "before's control held no cell of the lost patch: "//str(nb)//" bistable")
        if (allocated(error)) return
        m = a; m(2, 6) = .true.
        call patch_changes(a, b, made, lost, cm, cl, at_before=[cell_set(m)], at_after=[cell_set(b)], bistable=nb)
        call check(error, nb == 1, "before's control held a cell of the made patch: "//str(nb)//" bistable")
        if (allocated(error)) return
        ! without the earlier states: none
        call patch_changes(a, b, made, lost, cm, cl, bistable=nb)
        call check(error, nb == 0 .and. made == 1 .and. lost == 1 .and. cm == 3 .and. cl == 4, &
                   "no earlier states: "//str(nb)//" bistable")
        if (allocated(error)) return
        ! a patch lost across the y edge (one patch, its cells in the last and the first row), held
        ! by the second of two states at the after control through its first-row cell; the patch
        ! made is held by both
        a = .false.; b = .false.; m = .false.
        a(5, 12) = .true.; a(5, 1) = .true.
        b(10, 6) = .true.
        m(5, 1) = .true.; m(10, 6) = .true.
        call patch_changes(a, b, made, lost, cm, cl, at_before=[cell_set(a)], at_after=[cell_set(b), cell_set(m)], &
                           bistable=nb)
        call check(error, made == 1 .and. lost == 1 .and. cl == 2 .and. nb == 1, "across the y edge: made "// &
                   str(made)//", lost "//str(lost)//" ("//str(int(cl))//" cells), "//str(nb)//" bistable; expected"// &
                   " 1, 1 (2), 1")
        if (allocated(error)) return
        ! (a literal empty list, which gfortran 12 passes as absent: no earlier state either way)
        call patch_changes(a, b, made, lost, cm, cl, at_before=[cell_set_t ::], at_after=[cell_set_t ::], bistable=nb)
        call check(error, nb == 0, "empty lists: "//str(nb)//" bistable")
    end subroutine test_patches_bistable

end module test_veslide_anisotropy
