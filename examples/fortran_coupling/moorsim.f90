! Fortran bindings (ISO_C_BINDING) to the part of moorsim's C API (moorsim/moorsim.h) that
! a coupling uses: the lines of a scenario, stepped along the body's motion.
module moorsim
  use, intrinsic :: iso_c_binding
  implicit none
  integer(c_int), parameter :: MOORSIM_OK = 0

  interface
    function moorsim_lines_create(path) bind(C, name="moorsim_lines_create")
      import :: c_ptr, c_char
      character(kind=c_char), dimension(*), intent(in) :: path
      type(c_ptr) :: moorsim_lines_create
    end function

    subroutine moorsim_lines_destroy(lines) bind(C, name="moorsim_lines_destroy")
      import :: c_ptr
      type(c_ptr), value :: lines
    end subroutine

    integer(c_int) function moorsim_lines_count(lines, count) bind(C, name="moorsim_lines_count")
      import :: c_ptr, c_int
      type(c_ptr), value :: lines
      integer(c_int), intent(out) :: count
    end function

    integer(c_int) function moorsim_lines_init(lines, x, xd) bind(C, name="moorsim_lines_init")
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: lines
      real(c_double), intent(in) :: x(6), xd(6)
    end function

    integer(c_int) function moorsim_lines_step(lines, x, xd, f, t, dt) &
        bind(C, name="moorsim_lines_step")
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: lines
      real(c_double), intent(in) :: x(6), xd(6)
      real(c_double), intent(out) :: f(6)
      real(c_double), intent(inout) :: t, dt
    end function

    integer(c_int) function moorsim_lines_fairlead_tensions(lines, tensions, n) &
        bind(C, name="moorsim_lines_fairlead_tensions")
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: lines
      real(c_double), intent(out) :: tensions(*)
      integer(c_int), value :: n
    end function

    function moorsim_last_error_c() bind(C, name="moorsim_last_error")
      import :: c_ptr
      type(c_ptr) :: moorsim_last_error_c
    end function

    function strlen(s) bind(C, name="strlen")
      import :: c_ptr, c_size_t
      type(c_ptr), value :: s
      integer(c_size_t) :: strlen
    end function
  end interface

contains

  ! The calling thread's last error message as a Fortran string.
  function moorsim_last_error() result(message)
    character(len=:), allocatable :: message
    type(c_ptr) :: p
    character(kind=c_char), pointer :: chars(:)
    integer :: i, n
    p = moorsim_last_error_c()
    n = int(strlen(p))
    call c_f_pointer(p, chars, [n])
    allocate(character(len=n) :: message)
    do i = 1, n
      message(i:i) = chars(i)
    end do
  end function
end module moorsim
